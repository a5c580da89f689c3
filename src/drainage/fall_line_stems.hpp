// Creases drawn along the continuous fall line (the steepest descent of the smooth surface, as D∞
// directions take it: Tarboton, "A new method for the determination of flow directions and
// upslope areas in grid digital elevation models") instead of the D8 cells' staircase, keeping the
// network: every stem keeps its vertices (one a D8 cell, its flow and order) and its source; each
// vertex gets a new plan x, y (z is left to the drape).
// Per stem, in the drainage grid's index space (c east, r south; fine cells):
// 1. centre line S: the cells' path smoothed by a Gaussian of `sigma` cells along the stem (ends
//    fixed, the path reflected through them);
// 2. from the source, vertex k + 1 is one step |S(k + 1) - S(k)| from vertex k along the fall
//    direction of the DEM's own surface: the central differences at the DEM's nodes (g.coarse_z
//    at factor > 1, g.z at factor 1), bilinear between the four around the point (the field
//    lines/stroke_directions.hpp measures against; the resampled PN grid's own differences bend
//    the trace off it by a fraction of a DEM cell, which on a V-shaped valley floor is a large
//    angle); turned into the index frame with the grid's metric from grid_xy at the source's
//    cell, so non-square and UTM-projected cells give the plan's steepest descent; taken as
//    Heun's step, the mean of the directions at vertex k and one step along its own (a trace
//    reaching a valley's floor runs along it instead of zigzagging across). Where the fall line
//    leaves the stem's direction by more than 70 degrees, on flats or beside nodata, the vertex
//    moves with S and a fifth of the way back to it (at most half a step) instead; a vertex farther from S(k + 1) than
//    the corridor is drawn back onto that circle. The corridor is `corridor` cells at the source;
//    it widens by `widen` cells a cell of S while the slope exceeds widen_min_slope_deg and the
//    fall line runs within widen_max_deg of the stem (a plane or a cone, where a D8 path runs up
//    to 22.5 degrees off the fall line: the trace keeps to the fall line), up to `max_corridor`,
//    and narrows at the same rate elsewhere (flats, where the fall line heads for another valley);
//    in a valley the fall lines converge on the floor the D8 path follows and it does not bind.
//    Where the fall line, or a step, would leave the grid the trace stops: the stem's remaining
//    vertices stay where it stopped (no run along the grid's edge, no jump back to S);
// 3. plan x, y from grid_xy_at (the resampler's interpolation). The last vertex is where the trace
//    ends; a stem ending at a junction ends where its trace first comes within `meet` of the line
//    it joins, or where its trace ends when it never does (draped_lines.cpp: smooth_stems): a
//    junction the fall line does not lead to (D8 paths merge where a cone's fall lines never do)
//    is not drawn, and no tributary bends aside into its junction.
// Deterministic, one stem per task on all cores.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/drainage_grid.hpp"
#include "drainage/line_set.hpp"

namespace penink {

struct FallLineOptions {
    double sigma = 2.0;                // cells
    double corridor = 3.0;             // cells, at the source
    double widen = 0.5;                // corridor cells a cell of the stem's length
    double widen_max_deg = 30.0;       // widening while the fall line runs this close to the stem
    double widen_min_slope_deg = 5.0;  // and the slope is steeper
    double max_corridor = 60.0;        // cells
    double meet = 3.0;                 // cells: a stem ending at a junction ends where its trace
                                       // first comes this close to the line it joins (smooth_stems)
    double max_corridor_dem_cells = 20.0;  // fall_line_options' max_corridor, in DEM cells
};

// The build's options on a grid: sigma and corridor one DEM cell (the factor; at least 2 and 3
// cells), meet one corridor, max_corridor max_corridor_dem_cells DEM cells.
FallLineOptions fall_line_options(const DrainageGrid& g);

// Moves the x, y of each stem of `set` (network_stems with its `cells`) onto its fall line.
void trace_fall_lines(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                      const FallLineOptions& options);

}  // namespace penink
