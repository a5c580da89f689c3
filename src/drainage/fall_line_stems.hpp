// Creases drawn along the continuous fall line (the steepest descent of the smooth surface, as D∞
// directions take it: Tarboton, "A new method for the determination of flow directions and
// upslope areas in grid digital elevation models") instead of the D8 cells' staircase, keeping the
// network: every stem keeps its vertices (one a D8 cell, its flow and order) and its source; each
// vertex gets a new plan x, y (z is left to the drape).
// Per stem, in the drainage grid's index space (c east, r south; fine cells):
// 1. centre line S: the cells' path smoothed by a Gaussian of `sigma` cells along the stem (ends
//    fixed, the path reflected through them);
// 2. from the source, vertex k + 1 is one step |S(k + 1) - S(k)| from vertex k along the fall
//    direction of the grid's surface there (central differences of g.z at the four nodes around,
//    bilinear; turned into the index frame with the grid's metric from grid_xy at the source's
//    cell, so non-square and UTM-projected cells give the plan's steepest descent); where the fall line leaves the stem's
//    direction by more than 70 degrees, on flats or beside nodata, the vertex moves with S and
//    a fifth of the way back to it instead; a vertex farther than `corridor` cells from S(k) is
//    drawn back onto that circle;
// 3. plan x, y from grid_xy_at (the resampler's interpolation). The last vertex is where the trace ends;
//    a stem ending at a junction is brought back to it afterwards (draped_lines.cpp: join_ends).
// Deterministic, one stem per task on all cores.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/drainage_grid.hpp"
#include "drainage/line_set.hpp"

namespace penink {

struct FallLineOptions {
    double sigma = 2.0;     // cells
    double corridor = 3.0;  // cells
};

// The build's options on a grid: sigma and corridor one DEM cell (the factor; at least 2 and 3
// cells). A wider corridor lets a stem leave its D8 cells farther: on a cone, where the D8 paths
// run up to 22.5 degrees off the radial fall lines, 20 DEM cells draw radial creases; on real
// DEMs one cell keeps them nearest the valley floors the D8 paths find (bench/stroke_directions_bench).
FallLineOptions fall_line_options(const DrainageGrid& g);

// Moves the x, y of each stem of `set` (network_stems with its `cells`) onto its fall line.
void trace_fall_lines(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                      const FallLineOptions& options);

}  // namespace penink
