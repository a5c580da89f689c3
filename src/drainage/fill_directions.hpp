// Depression filling (priority_flood.hpp) and D8 directions on the filled surface (d8.hpp) on all
// cores: the fill in row bands (banded_fill.hpp), then D8 in two halves; or, on one band, the fill
// on one thread (priority_flood_levels leaves z as it is) while another takes the D8 directions
// of the ORIGINAL elevations: a cell's filled and original 3x3 blocks differ only where the block
// holds a raised cell, and those cells are redone on the filled surface afterwards.
// Grid: row-major, row 0 north, dx / dy metres, z local metres.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"
#include "drainage/priority_flood.hpp"
#include "drainage/routing_grid.hpp"

namespace penink {

// What priority_flood_fill(z, g.shape, flags, orig_bits) and then dir = d8_directions(z, g.shape,
// g.dx, g.dy, &ties) give, all but g in `arrays`: z filled, flags and orig_bits as the fill leaves
// them, dir, and ties holding the same cells (in another order: break_d8_ties sorts them).
// With several `bands` (0: fill_bands, one per core) the fill runs in row bands on all cores
// (banded_fill.hpp) with `scratch` as its label array (resized; pass one a later stage fills
// anew), then D8 on the filled surface; with one band the fill runs beside D8 on the original
// surface, the cells near raised ones redone after.
FillStats fill_with_directions(const RoutingGrid& g, RoutingArrays& arrays, CellWords& scratch, int bands = 0);

}  // namespace penink
