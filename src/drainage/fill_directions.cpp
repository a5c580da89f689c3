#include "drainage/fill_directions.hpp"

#include <algorithm>
#include <bit>
#include <exception>
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

}  // namespace penink
