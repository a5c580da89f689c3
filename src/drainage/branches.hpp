// Drainage lines and divides as vertex lists (seed 000 sec. 3): every drainage point belongs to
// one branch — a run from a source (ridge point, no inflow) or a junction (inflow > 1) down
// through single-inflow points to the next junction (repeated as the branch's last vertex) or
// an outlet; all flow paths are kept (thresholding happens at render time by the score).
// Divides: the boundary between 4-adjacent valid points of different basins, i.e. the dual-grid
// edges between them, chained at dual corners into polylines (corner = mean x, y of its valid
// surrounding points, z = their highest elevation; flow 0).
#pragma once
#include "drainage/drainage_db.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/flow_network.hpp"

namespace penink {

// Fills db.vertices, db.branches and db.upstream (branches in row-major order of their head).
// z comes from g.z (pass the original, unfilled elevations).
void build_branches(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                    const FlowNetwork& net, DrainageDb& db);

// Fills db.divide_vertices and db.divides.
void build_divides(const DrainageGrid& g, const FlowNetwork& net, DrainageDb& db);

}  // namespace penink
