// Ties between equally steep D8 neighbours broken by looking downstream: of the tied neighbours a
// cell drains to the one whose own flow path gets lower sooner (lexicographic comparison of the
// original elevations, metres, along each candidate's path for up to `depth` steps; a path that
// leaves the grid counts as lowest; still equal: the lowest ESRI code). A fixed neighbour order
// alone bends flow towards one compass direction wherever ties are common (DEMs stored in whole
// metres: 6 % of volcano's sloping cells); a least-cost search from the outlets (GRASS
// r.watershed's A*) settles the same ties by how early each candidate was reached from lower
// ground, which the downstream comparison follows.
// Candidates are recomputed as the stages chose them: a raised cell off the outflow paths
// (depression_drainage.hpp) among neighbours lower on the original DEM; a flat cell among its
// neighbours of least flat gradient (flat_resolution.hpp); any other cell among neighbours lower
// on the filled surface, slopes on the original elevations (d8.hpp, the rims:
// depression_drainage.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"
#include "drainage/routing_grid.hpp"

namespace penink {

// arrays.ties: cells reported tied by the direction stages (duplicates allowed; left
// deduplicated and sorted in the order settled); arrays.z (filled), arrays.flags,
// arrays.orig_bits: the fill's state (priority_flood.hpp); `flat_mask`: the flat gradients
// resolve_flats left; arrays.dir re-aimed in place, lower cells first (on one level: flat cells
// nearer their exit first). Returns the number of cells whose direction changed.
std::size_t break_d8_ties(const RoutingGrid& g, RoutingArrays& arrays, const CellWords& flat_mask, int depth = 16);

}  // namespace penink
