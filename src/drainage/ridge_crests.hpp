// Ridges drawn on the surface's crest instead of along the dual grid's staircase: a basin divide
// (branches.hpp: the edges between cells of different basins, chained at dual corners) runs in
// unit steps east-west and north-south, and a Gaussian along it (polyline_smoothing.hpp) leaves its
// long straight runs on the grid's axes. Each interior vertex of a smoothed divide moves across
// its line (along the plan normal of the chord between its neighbours) to the highest point of
// the DEM's PN surface (dem_surface.hpp) within `reach` metres: 2 m + 1 samples across, the top
// refined by the parabola through the best sample and its two neighbours; the move fades in from
// the line's ends over `fade` vertices (ends fixed: the divides' junctions stay joined); then the
// line is smoothed again by a Gaussian of `sigma` vertices (the crest of a noisy DEM wanders by a
// fraction of a cell from vertex to vertex). A vertex off the surface, or with a neighbour off it,
// stays. Frame: the Terrain's local metres; z untouched (the drape sets it).
// Deterministic, lines on all cores.
#pragma once
#include "drainage/dem_surface.hpp"
#include "drainage/line_set.hpp"

namespace penink {

struct CrestOptions {
    double reach = 30.0;  // metres each side
    int samples = 3;      // m: samples each side of the vertex
    int fade = 6;         // vertices
    double sigma = 2.0;   // vertices
};

// The build's options on a grid: reach one and a half DEM cells, fade and sigma three and one
// DEM cells of vertices (the divides' vertices are one fine cell apart).
CrestOptions crest_options(const DrainageGrid& g);

// Moves each interior vertex of `set` (x, y) onto the crest (see above).
void snap_to_crests(DrapedLineSet& set, const DemSurface& surface, const CrestOptions& options);

}  // namespace penink
