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
// The ties are settled in one order (lowest first) and a tie's choice reads the directions along
// its candidates' paths, within `depth` cells of it: on several threads, rows are cut into strips
// and a tie near a strip's edge waits for the neighbouring strip's ties near it that come before
// it in the order, so every tie reads what it would one by one (d8_ties.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"
#include "drainage/routing_grid.hpp"

namespace penink {

// How break_d8_ties spreads the settling over threads (the result is the same): `threads` (0:
// the hardware's, up to 16, where it has 4 or more, else 1; 1: one by one), the rows of a strip
// (0: rows / (8 threads), 8 depth to 1024; at least depth + 1) and the columns of a run of a
// strip's edge that waits apart from the others (0: 32; at least depth). Automatic: one by one
// below 2^16 ties.
struct TieThreads {
    unsigned threads = 0;
    int strip_rows = 0;
    int segment_cols = 0;
};

// arrays.ties: cells reported tied by the direction stages (duplicates allowed; left
// deduplicated and sorted in the order settled); arrays.z (filled), arrays.flags,
// arrays.orig_bits: the fill's state (priority_flood.hpp), orig_bits then completed with the
// filled elevations of the cells not raised (every cell's original elevation, one array to read
// per path step); `flat_mask`: the flat gradients resolve_flats left; arrays.dir re-aimed in
// place, lower cells first (on one level: flat cells nearer their exit first). Each tie's
// candidates are found in a pass over the ties in cell order (parallel), then the ties sorted
// into the settling order. Returns the number of cells whose direction changed.
std::size_t break_d8_ties(const RoutingGrid& g, RoutingArrays& arrays, const CellWords& flat_mask, int depth = 16,
                          TieThreads split = {});

}  // namespace penink
