// D8 steepest-descent flow directions (O'Callaghan & Mark 1984) on a row-major grid (row 0 north)
// with ESRI codes: 1=E, 2=SE, 4=S, 8=SW, 16=W, 32=NW, 64=N, 128=NE, 0 = no downhill neighbour.
// Drop per distance: cardinal steps dx (E/W) or dy (N/S) metres, diagonals hypot(dx, dy).
#pragma once
#include "core/big_allocator.hpp"
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penink {

// Per-cell 32-bit values (accumulation, basin labels, and the fill's and flats' scratch that
// borrows their arrays): grown without zero-filling (UninitAllocator: large blocks mapped with
// huge pages, first touched where they are written, on the threads that write them); every
// reader reads only what a stage wrote.
using CellWords = std::vector<std::uint32_t, UninitAllocator<std::uint32_t>>;
using CellBytes = std::vector<std::uint8_t, UninitAllocator<std::uint8_t>>;

// Neighbour k = 0..7 in ESRI code order E, SE, S, SW, W, NW, N, NE; code = 1 << k.
inline constexpr int d8_dc[8] = {1, 1, 0, -1, -1, -1, 0, 1};
inline constexpr int d8_dr[8] = {0, 1, 1, 1, 0, -1, -1, -1};
inline int d8_index(std::uint8_t code) { return std::countr_zero(unsigned(code)); }

// Row-major grid shape plus the valid mask, for neighbour walks.
struct GridShape {
    int cols = 0, rows = 0;
    const std::uint8_t* valid = nullptr;  // cols*rows, 1 = data
    std::size_t size() const { return std::size_t(cols) * rows; }
};

// Linear index offsets of the 8 neighbours (code order) on a grid of g.cols columns.
inline std::array<std::ptrdiff_t, 8> d8_offsets(const GridShape& g) {
    std::array<std::ptrdiff_t, 8> off{};
    for (int k = 0; k < 8; ++k) off[k] = std::ptrdiff_t(d8_dr[k]) * g.cols + d8_dc[k];
    return off;
}

// Linear index of the neighbour the ESRI `code` at cell i points to.
inline std::size_t d8_target(const GridShape& g, std::size_t i, std::uint8_t code) {
    const int k = d8_index(code);
    return std::size_t(std::ptrdiff_t(i) + std::ptrdiff_t(d8_dr[k]) * g.cols + d8_dc[k]);
}

// True for a valid cell on the grid border or 8-adjacent to a nodata cell: when nothing around
// it is lower it drains out of the grid (an outlet) instead of being a pit or flat.
bool is_boundary_cell(const GridShape& g, int c, int r);

// Steepest strictly-downhill valid neighbour per valid cell (first in code order on ties: the
// lowest ESRI code), 0 when none or invalid. Runs of interior cells whose 3x3 block is all data
// take a branch-free loop the compiler vectorises across cells; the south half of the rows runs on a
// second thread (unless two_threads is false). When `ties` is given, the cells whose steepest
// slope is shared by two or more neighbours are appended to it (for break_d8_ties, d8_ties.hpp).
std::vector<std::uint8_t> d8_directions(const std::vector<float>& z, const GridShape& g,
                                        double dx, double dy,
                                        std::vector<std::uint32_t>* ties = nullptr,
                                        bool two_threads = true);

}  // namespace penink
