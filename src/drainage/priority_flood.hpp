// Depression filling by Priority-Flood (Barnes, Lehman & Mulla 2014, "Priority-flood: An optimal
// depression-filling and watershed-labeling algorithm", Alg. 2, plain FIFO/stack for cells raised
// into depressions) with the improvement of Zhou, Sun & Fu 2016 ("An efficient variant of the
// Priority-Flood algorithm for filling depressions in raster DEMs"): cells on slopes are traced
// uphill without the priority queue; only a traced cell that still has an open lower neighbour
// goes through the queue, a radix heap on order-preserving elevation keys (Ahuja et al. 1990:
// exact, since no cell is queued below the level being spilled). Every closed depression is
// raised to its spill elevation (leaving flats that the flat resolution drains). Seeds are the
// valid boundary cells (grid border or next to nodata, see d8.hpp), so every valid cell ends up
// with a non-ascending path to one.
// The filled surface is unique, so the result does not depend on the queue order.
#pragma once
#include <cstdint>
#include <vector>

#include "core/parallel_chunks.hpp"
#include "drainage/d8.hpp"

namespace penink {

// Bits of the per-cell fill state (`flags`); bits 2, 3 and 5..7 are free for later stages.
inline constexpr std::uint8_t fill_closed = 1;  // filled elevation known (or nodata)
inline constexpr std::uint8_t fill_raised = 2;  // the fill raised the cell (filled > original)
inline constexpr std::uint8_t fill_boundary = 16;  // a seed: valid boundary cell (d8.hpp)

struct FillStats {
    std::size_t raised = 0;  // cells raised into depressions
    std::size_t queued = 0;  // cells that went through the priority queue (seeds included)
    std::size_t labels = 0;  // a band's fill: watersheds its edge seeds started (band_flood.hpp)
};

// Fills `z` (cols*rows, row-major, local metres) in place. `flags` is resized to cols*rows and
// set to fill_closed (| fill_raised where raised, | fill_boundary on seeds); for every raised cell i, orig_bits[i] receives
// std::bit_cast<uint32_t>(original z) (a uint32 buffer so the build can lend it the accumulation
// array; resized to cols*rows, other entries left as they are). = priority_flood_levels, then
// swap_raised.
FillStats priority_flood_fill(std::vector<float>& z, const GridShape& g,
                              std::vector<std::uint8_t>& flags,
                              CellWords& orig_bits);

// The same fill leaving `z` as it is (only read: another thread may read it meanwhile): the
// filled level of every raised cell i goes to level_bits[i] (float bits).
FillStats priority_flood_levels(const std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                                CellWords& level_bits);

// Whether cell (c, r) has a raised neighbour (one of its 8, on the grid), from the fill's flags.
bool next_to_raised(const GridShape& g, const std::vector<std::uint8_t>& flags, int c, int r);

// Row r at once: near[c] != 0 exactly where the 3x3 block around (c, r) on the grid holds a
// raised cell (the cell itself or next_to_raised). near has g.cols bytes; `column` is scratch.
void near_raised_row(const GridShape& g, const std::vector<std::uint8_t>& flags, int r,
                     std::vector<std::uint8_t>& column, std::uint8_t* near);

// Calls f(c, r, i, out) for every valid cell i = (c, r) near a raised cell (near_raised_row), rows
// in parallel chunks (f may write cell i's own data only); returns what the calls appended to
// `out`, in row-major order.
template <class F>
std::vector<std::uint32_t> collect_near_raised(const GridShape& g, const std::vector<std::uint8_t>& flags, F&& f) {
    return parallel_collect<std::uint32_t>(
        std::size_t(g.rows), 64, [&](std::size_t r0, std::size_t r1, std::vector<std::uint32_t>& out) {
            std::vector<std::uint8_t> column, near(std::size_t(g.cols));
            for (int r = int(r0); r < int(r1); ++r) {
                near_raised_row(g, flags, r, column, near.data());
                for (int c = 0; c < g.cols; ++c) {
                    const std::size_t i = std::size_t(r) * g.cols + c;
                    if (near[std::size_t(c)] && g.valid[i]) f(c, r, i, out);
                }
            }
        });
}

// Exchanges z[i] with the float bits in bits[i] at every raised cell: after priority_flood_levels
// z becomes the filled surface and bits the original elevations; done again, z is the original.
void swap_raised(std::vector<float>& z, const std::vector<std::uint8_t>& flags, CellWords& bits);

// Original elevation of cell i (z holds the filled surface).
inline float original_z(const std::vector<float>& z, const std::vector<std::uint8_t>& flags,
                        const CellWords& orig_bits, std::size_t i) {
    return flags[i] & fill_raised ? std::bit_cast<float>(orig_bits[i]) : z[i];
}

}  // namespace penink
