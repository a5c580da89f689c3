// Least-cost search flow routing (Ehlschlaeger 1989; Metz, Mitasova & Harmon 2011, HESS 15: the
// method of GRASS GIS `r.watershed -s`): ESRI D8 directions (d8.hpp codes, 0 = drains off the
// grid) from the unfilled elevations z (metres, row-major, row 0 north; spacing dx east, dy south
// in metres) by a search that spreads uphill from the boundary cells, lowest cell first.
//
// The search, as r.watershed does it (GRASS 8.2, checked against it on volcano.asc):
//  - Priority: the cell's own elevation, then the insertion counter (equal elevations leave the
//    queue oldest first). Elevations are compared as floats; GRASS rounds floating-point DEMs to
//    millimetres (integer DEMs such as volcano compare identically), so on float DEMs cells less
//    than 1 mm apart may be ordered differently from GRASS.
//  - Seeds, in row-major order: every valid cell on the grid border or next to nodata; a seed
//    drains off the grid (code 0) unless redirected.
//  - A popped cell c visits its neighbours in GRASS's order S, N, W, E, NE, SW, SE, NW; popped
//    and nodata neighbours are passed over. slope(n) = (z_n - z_c) / distance when z_n > z_c,
//    else 0. A neighbour n not yet queued is queued (key z_n) and drains to c; a queued seed
//    still draining off the grid is redirected to c, but only when slope(n) > 0.
//  - Diagonal-bias check, before either, for a diagonal n with slope(n) > 0: n is left alone
//    (reached later from elsewhere) when one of the two orthogonal neighbours o of c beside it
//    is still unpopped (o on the grid, valid, not popped; its own slope may be 0) and
//    slope(n) < (z_n - z_o) / |o n| (0 when z_n <= z_o).
//    (GRASS 8.2's observed behaviour on volcano and small test grids: counting only orthogonal
//    neighbours with slope(o) > 0, or redirecting seeds from equal ground, agrees on 75 %.)
//  - Directions never change otherwise; depressions are not filled: the search enters them from
//    their spill and their cells drain along the search tree back to it.
// Queue: a radix heap of 8-byte entries (32-bit elevation key, cell) for the keys at or above
// the level being searched, first in first out among equal keys (FifoRadixHeap: the insertion
// order without a counter), a binary heap on (key, counter) for the few below it (inside
// depressions). The grid is copied into a frame one nodata cell wider (elevation keys, one byte
// per cell for state and direction), so neighbours need no bounds checks; the next cell to pop
// is prefetched one visit ahead. 3.47 M cells (jacksboro refined to 2015x1720) in about 0.29 s,
// 4.2 M cells (2048^2 fractal) in about 0.45 s: `PENINK_BENCH_DEM=DEM drainage_bench
// --benchmark_filter=LeastCost`; the search's memory besides the output is 5 bytes per cell
// plus the queue.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"

namespace penink {

// ESRI D8 code per cell (0 for outlets and invalid cells); every valid cell reaches an outlet.
std::vector<std::uint8_t> least_cost_directions(const std::vector<float>& z, const GridShape& shape,
                                                double dx, double dy);

}  // namespace penink
