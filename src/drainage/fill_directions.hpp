// Depression filling (priority_flood.hpp) and D8 directions on the filled surface (d8.hpp) on all
// cores: the fill in row bands (banded_fill.hpp), then D8 in two halves; or, on one band, the fill
// on one thread (priority_flood_levels leaves z as it is) while another takes the D8 directions
// of the ORIGINAL elevations: a cell's filled and original 3x3 blocks differ only where the block
// holds a raised cell, and those cells are redone on the filled surface afterwards.
// Grid: row-major, row 0 north, dx / dy metres, z local metres.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "drainage/d8.hpp"
#include "drainage/priority_flood.hpp"
#include "drainage/routing_grid.hpp"
#include "drainage/tiled_fill.hpp"

namespace penink {

// What priority_flood_fill(z, g.shape, flags, orig_bits) and then dir = d8_directions(z, g.shape,
// g.dx, g.dy, &ties) give, all but g in `arrays`: z filled, flags and orig_bits as the fill leaves
// them, dir, and ties holding the same cells (in another order: break_d8_ties sorts them).
// With several `bands` (0: fill_bands, one per core) the fill runs in row bands on all cores
// (banded_fill.hpp) with `scratch` as its label array (resized; pass one a later stage fills
// anew), then D8 on the filled surface; with one band the fill runs beside D8 on the original
// surface, the cells near raised ones redone after.
FillStats fill_with_directions(const RoutingGrid& g, RoutingArrays& arrays, CellWords& scratch, int bands = 0);

// A fill made elsewhere (by other processes too: tiled_fill.hpp's distributed_priority_flood):
// given the grid and its heights z, hands the filled levels (priority_flood_fill's surface: each
// valid cell's bit for bit; a nodata cell's any value) of every row to `rows`, bands of rows in
// row order.
using ExternalFill = std::function<void(const GridShape& g, const std::vector<float>& z, const FillRowWriter& rows)>;

// The fill state priority_flood_levels leaves, from filled levels made elsewhere: for rows
// [y0, y1) (levels: their (y1 - y0) x cols levels), flags set to fill_closed, | fill_raised where
// the level is above z, | fill_boundary on valid boundary cells (is_boundary_cell), and
// level_bits[i] = the level's bits at every raised cell i (flags and level_bits cols x rows;
// others left as they are). Returns the cells raised.
std::size_t fill_state_of_rows(const std::vector<float>& z, const GridShape& g, int y0, int y1, const float* levels,
                               std::vector<std::uint8_t>& flags, CellWords& level_bits);

// fill_with_directions with the fill made by `fill` (its levels through fill_state_of_rows), then
// D8 on the filled surface on all cores: the same arrays (stats: the cells raised).
FillStats fill_with_directions(const RoutingGrid& g, RoutingArrays& arrays, const ExternalFill& fill);

}  // namespace penink
