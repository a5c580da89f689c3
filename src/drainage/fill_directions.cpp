#include "drainage/fill_directions.hpp"

#include <algorithm>
#include <bit>
#include <exception>
#include <stdexcept>
#include <thread>

#include "core/parallel_chunks.hpp"
#include "drainage/banded_fill.hpp"
#include "drainage/d8_steepest.hpp"

namespace penink {

namespace {

// Whether the 3x3 block around cell (c, r) holds a raised cell.
bool near_raised(const GridShape& g, const std::vector<std::uint8_t>& flags, int c, int r) {
    return (flags[std::size_t(r) * g.cols + c] & fill_raised) || next_to_raised(g, flags, c, r);
}

// Directions (and ties) of the cells near raised ones taken again on z, the filled surface;
// rows in parallel chunks (a cell writes only its own direction).
void redo_near_raised(const RoutingGrid& grid, RoutingArrays& arrays) {
    const GridShape& g = grid.shape;
    const std::vector<float>& z = arrays.z;
    const std::vector<std::uint8_t>& flags = arrays.flags;
    std::vector<std::uint8_t>& dir = arrays.dir;
    std::vector<std::uint32_t>& ties = arrays.ties;
    const auto cols = std::uint32_t(g.cols);
    std::erase_if(ties, [&](std::uint32_t i) { return near_raised(g, flags, int(i % cols), int(i / cols)); });
    const D8Steps st = d8_steps(g, grid.dx, grid.dy);
    auto zn = [&](std::size_t n) { return z[n]; };
    const std::vector<std::uint32_t> tied = collect_near_raised(
        g, flags, [&](int c, int r, std::size_t i, std::vector<std::uint32_t>& out) {
            const D8Choice d = d8_steepest(z[i], g, c, r, st, zn, [](std::size_t) { return true; });
            dir[i] = d.code();
            if (d.tie()) out.push_back(std::uint32_t(i));
        });
    ties.insert(ties.end(), tied.begin(), tied.end());
}

}  // namespace

FillStats fill_with_directions(const RoutingGrid& grid, RoutingArrays& arrays, CellWords& scratch, int bands) {
    const GridShape& g = grid.shape;
    FillStats st;
    if (bands <= 0) bands = fill_bands(g.rows);
    if (bands > 1) {  // the fill takes every core, then D8 on the filled surface
        st = priority_flood_levels_banded(arrays.z, g, arrays.flags, arrays.orig_bits, scratch, bands);
        swap_raised(arrays.z, arrays.flags, arrays.orig_bits);
        arrays.dir = d8_directions(arrays.z, g, grid.dx, grid.dy, &arrays.ties);
        return st;
    }
    // D8 reads z and g only, like the fill
    run_beside([&] { arrays.dir = d8_directions(arrays.z, g, grid.dx, grid.dy, &arrays.ties, false); },
               [&] { st = priority_flood_levels(arrays.z, g, arrays.flags, arrays.orig_bits); });
    swap_raised(arrays.z, arrays.flags, arrays.orig_bits);
    redo_near_raised(grid, arrays);
    return st;
}

std::size_t fill_state_of_rows(const std::vector<float>& z, const GridShape& g, int y0, int y1, const float* levels,
                               std::vector<std::uint8_t>& flags, CellWords& level_bits) {
    std::size_t raised = 0;
    const std::size_t cols = std::size_t(g.cols);
    for (int r = y0; r < y1; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * cols + std::size_t(c);
            std::uint8_t f = fill_closed;
            if (g.valid[i]) {
                const float level = levels[std::size_t(r - y0) * cols + std::size_t(c)];
                if (level > z[i]) f |= fill_raised, level_bits[i] = std::bit_cast<std::uint32_t>(level), ++raised;
                if (is_boundary_cell(g, c, r)) f |= fill_boundary;
            }
            flags[i] = f;
        }
    return raised;
}

FillStats fill_with_directions(const RoutingGrid& grid, RoutingArrays& arrays, const ExternalFill& fill) {
    const GridShape& g = grid.shape;
    const std::size_t n = std::size_t(g.cols) * std::size_t(g.rows);
    arrays.flags.resize(n);
    arrays.orig_bits.resize(n);
    FillStats st;
    int next = 0;
    fill(g, arrays.z, [&](int y0, int y1, const float* levels, const std::uint8_t*) {
        if (y0 != next || y1 <= y0 || y1 > g.rows) throw std::runtime_error("fill: rows handed over out of order");
        st.raised += fill_state_of_rows(arrays.z, g, y0, y1, levels, arrays.flags, arrays.orig_bits);
        next = y1;
    });
    if (next != g.rows) throw std::runtime_error("fill: rows missing from the fill handed over");
    swap_raised(arrays.z, arrays.flags, arrays.orig_bits);
    arrays.dir = d8_directions(arrays.z, g, grid.dx, grid.dy, &arrays.ties);
    return st;
}

}  // namespace penink
