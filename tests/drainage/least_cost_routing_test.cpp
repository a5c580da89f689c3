// Least-cost search routing (least_cost_routing.hpp) on hand-made grids, 1 m cells, row 0 north.
// Expected ESRI codes (1 E, 2 SE, 4 S, 8 SW, 16 W, 32 NW, 64 N, 128 NE, 0 off the grid) are
// worked out by hand from the search's rules below each grid; every grid was also run through
// GRASS 8.2 `r.watershed -s`, which gives the same codes (its off-map codes are our 0).
// Plus the plumbing: compute_drainage and `penink drainage` with the routing, and the fingerprint.
#include <algorithm>
#include <filesystem>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/least_cost_routing.hpp"

namespace penink {
namespace {

std::vector<std::uint8_t> route(int cols, int rows, const std::vector<float>& z,
                                std::vector<std::uint8_t> valid = {}) {
    if (valid.empty()) valid.assign(z.size(), 1);
    const GridShape shape{cols, rows, valid.data()};
    return least_cost_directions(z, shape, 1.0, 1.0);
}

// Falls 1 m per row to the south. The bottom row pops first and its cells drain off the grid;
// every other cell is reached from the cell below it: each bottom cell's diagonal neighbour is
// skipped because the still unqueued orthogonal neighbour beside it (equal to the popped cell,
// slope 0) lies 1 m below it over 1 m, steeper than the diagonal's 1 m over 1.41 m. The west
// and east border seeds are redirected south by the lower cell below them, the top row too.
TEST(LeastCostRouting, TiltedPlaneDrainsStraightDownSlope) {
    const std::vector<float> z = {3, 3, 3, 3, 3,
                                  2, 2, 2, 2, 2,
                                  1, 1, 1, 1, 1,
                                  0, 0, 0, 0, 0};
    const std::vector<std::uint8_t> expected = {4, 4, 4, 4, 4,
                                                4, 4, 4, 4, 4,
                                                4, 4, 4, 4, 4,
                                                0, 0, 0, 0, 0};
    EXPECT_EQ(route(5, 4, z), expected);
}

// A flat 3x3 floor at 1 m in a 9 m rim, outlet (4,2) at 0 m (cells as (row, col)). The outlet
// pops first, redirects the rim cells beside it inward (W one E, E one W) and queues (3,2) (its N:
// drains S), (3,3) (NE: drains SW) and (3,1) (NW: drains SE), in that order. The floor then pops
// oldest first, each cell queuing its fresh neighbours in the order S, N, W, E, NE, SW, SE, NW:
// (3,2) queues (2,2) S, (2,3) SW, (2,1) SE; (3,3) and (3,1) find nothing new; (2,2) queues
// (1,2) S, (1,3) SW, (1,1) SE. So the floor drains breadth-first to the cell it was first reached
// from: column 1 SE, column 2 S, column 3 SW. Each rim seed is redirected by the first lower
// floor cell that pops next to it (the corners diagonally: no orthogonal neighbour beside them
// rises more steeply; (2,0) is not taken diagonally from (3,1): (2,1) rises 8 m over 1 m).
TEST(LeastCostRouting, FlatFloorDrainsBreadthFirstInInsertionOrder) {
    const std::vector<float> z = {9, 9, 9, 9, 9,
                                  9, 1, 1, 1, 9,
                                  9, 1, 1, 1, 9,
                                  9, 1, 1, 1, 9,
                                  9, 9, 0, 9, 9};
    const std::vector<std::uint8_t> expected = {  2, 4, 4, 4,  8,
                                                  1, 2, 4, 8, 16,
                                                  1, 2, 4, 8, 16,
                                                  1, 2, 4, 8, 16,
                                                128, 1, 0, 16, 32};
    EXPECT_EQ(route(5, 5, z), expected);
}

// A pit (2,2) at 1 m inside a rim that spills at (4,3), 2 m. The spill pops first and queues
// (3,3) at 3 m (its N: drains S) and (3,2) at 4 m (NW: drains SE; the orthogonal (3,3) beside it
// rises only 1 m to it, less than the diagonal's 2 m over 1.41 m). (3,3) pops and queues (2,3)
// (N: drains S) and the pit (NW: drains SE; lower, so no diagonal check). The pit, now lowest in
// the queue, pops and queues the rest of the bowl, which drains into it: (1,2) S, (2,1) E,
// (1,3) SW, (3,1) NE, (1,1) SE. The pit drains along the search tree through (3,3) to the spill:
// 17 cells pass through the pit, all 25 reach the spill, the only outlet.
TEST(LeastCostRouting, ClosedDepressionDrainsThroughTheSearchTreeToItsSpill) {
    const std::vector<float> z = {9, 9, 9, 9, 9,
                                  9, 5, 4, 5, 9,
                                  9, 4, 1, 4, 9,
                                  9, 5, 4, 3, 9,
                                  9, 9, 9, 2, 9};
    const std::vector<std::uint8_t> expected = {  2,   4, 4, 4,  8,
                                                  1,   2, 4, 8, 16,
                                                  1,   1, 2, 4, 16,
                                                  1, 128, 2, 4, 16,
                                                128,  64, 1, 0, 16};
    EXPECT_EQ(route(5, 5, z), expected);
    DrainageGrid g = make_regular_grid(5, 5, 1.0, z);
    const DrainageResult res = compute_drainage(g, {}, DrainageRouting::least_cost);
    EXPECT_EQ(res.dir, expected);
    EXPECT_EQ(res.net.outlet, std::vector<std::uint32_t>{5 * 4 + 3});
    EXPECT_EQ(res.net.acc[5 * 2 + 2], 17u);
    EXPECT_EQ(res.net.acc[5 * 3 + 3], 21u);
    EXPECT_EQ(res.net.acc[5 * 4 + 3], 25u);
    EXPECT_EQ(res.stats.filled, 0u);  // nothing filled: the fill pass does not run
    EXPECT_EQ(g.z, z);
}

// Outlet (4,2) at 0 m below (3,2) at 1 m and (3,3) at 4 m, all else 9 m. Popping the outlet,
// the diagonal (3,3) is skipped: the orthogonal (3,2) beside it rises 3 m over 1 m to it, more
// than the diagonal's 4 m over 1.41 m (2.83). (3,3) is queued later by (3,2) and drains W, the
// orthogonal path, not SW straight to the outlet; likewise (3,1) (9 m) drains E to (3,2), not SE.
// (The other interior cells follow from (3,2)/(3,3) popping; border cells at 9 m next to no lower
// cell stay outlets.)
TEST(LeastCostRouting, DiagonalBiasCheckPrefersTheOrthogonalPath) {
    const std::vector<float> z = {9, 9, 9, 9, 9,
                                  9, 9, 9, 9, 9,
                                  9, 9, 9, 9, 9,
                                  9, 9, 1, 4, 9,
                                  9, 9, 0, 9, 9};
    const std::vector<std::uint8_t> expected = {0,  0,  0,  0,  0,
                                                0, 32, 32, 32,  0,
                                                0,  2,  4,  8,  8,
                                                0,  1,  4, 16, 16,
                                                0,  1,  0, 16, 32};
    const std::vector<std::uint8_t> dir = route(5, 5, z);
    EXPECT_EQ(dir[5 * 3 + 3], 16);  // the case built for it: W, not SW
    EXPECT_EQ(dir[5 * 3 + 1], 1);   // E, not SE
    EXPECT_EQ(dir, expected);
}

// Outlet (2,0) at 0 m; the interior row rises 1, 2, 3 m eastwards; all else 5 m. The outlet pops
// and redirects its border neighbours N and E to itself (lower: they drain S and W instead of off
// the grid) and queues (1,1). (1,1) at 1 m pops before any 5 m border seed and redirects (0,1)
// S and the corner (0,0) SE inward, but not (2,1), already redirected. (1,2) at 2 m redirects
// (2,2) N and (0,2) S; (0,3) and (2,3) diagonally (the orthogonal (1,3) rises only 2 m over 1 m,
// less than 3 m over 1.41 m). (1,3) redirects (1,4) W and the corners SW and NW. One outlet.
TEST(LeastCostRouting, BorderSeedIsRedirectedInwardByALowerInteriorCell) {
    const std::vector<float> z = {5, 5, 5, 5, 5,
                                  5, 1, 2, 3, 5,
                                  0, 5, 5, 5, 5};
    const std::vector<std::uint8_t> expected = { 2,  4,  4,  8,  8,
                                                 4,  8, 16, 16, 16,
                                                 0, 16, 64, 32, 32};
    const std::vector<std::uint8_t> dir = route(5, 3, z);
    EXPECT_EQ(dir[5 * 2 + 2], 64);  // a border seed drains N into the interior
    EXPECT_EQ(dir, expected);
}

// Nodata cells are passed over and the cells around them are seeds. On the plane of the first
// test with a hole at (2,2), the seed (1,2) above the hole is redirected first by (2,1), which
// pops (1 m) before (2,3): diagonally SW, the orthogonal beside the diagonal being the hole
// (ignored) and (1,1), level with (1,2). The seeds beside the hole drain S like the rest.
TEST(LeastCostRouting, CellsNextToNodataAreSeeds) {
    std::vector<float> z = {3, 3, 3, 3, 3,
                            2, 2, 2, 2, 2,
                            1, 1, 1, 1, 1,
                            0, 0, 0, 0, 0};
    std::vector<std::uint8_t> valid(z.size(), 1);
    valid[5 * 2 + 2] = 0;
    const std::vector<std::uint8_t> expected = {4, 4, 4, 4, 4,
                                                4, 4, 8, 4, 4,
                                                4, 4, 0, 4, 4,
                                                0, 0, 0, 0, 0};
    EXPECT_EQ(route(5, 4, z, valid), expected);
}

// The routing reaches the database: compute_drainage differs from the default where flats are
// drained, and `penink drainage` (DrainageCommand) records the routing in the fingerprint, so a
// cache built with the other routing is stale.
TEST(LeastCostRouting, RoutingReachesComputeDrainage) {
    const std::vector<float> z = {9, 9, 9, 9, 9,
                                  9, 1, 1, 1, 9,
                                  9, 1, 1, 1, 9,
                                  9, 1, 1, 1, 9,
                                  9, 9, 0, 9, 9};
    DrainageGrid g = make_regular_grid(5, 5, 1.0, z);
    const DrainageResult lc = compute_drainage(g, {}, DrainageRouting::least_cost);
    const DrainageResult pf = compute_drainage(g, {});
    EXPECT_EQ(lc.dir, route(5, 5, z));
    EXPECT_NE(pf.dir, lc.dir);

}

}  // namespace
}  // namespace penink
