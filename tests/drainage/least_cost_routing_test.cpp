// Least-cost search routing (least_cost_routing.hpp) on hand-made grids, 1 m cells, row 0 north.
// Expected ESRI codes (1 E, 2 SE, 4 S, 8 SW, 16 W, 32 NW, 64 N, 128 NE, 0 off the grid) are
// worked out by hand from the search's rules below each grid; every grid was also run through
// GRASS 8.2 `r.watershed -s`, which gives the same codes (its off-map codes are our 0).
// Plus the plumbing: compute_drainage and `penink drainage` with the routing, and the fingerprint,
// and the search against a plain reference of the same rules (std::priority_queue on elevation
// and insertion counter, bounds checks, slopes in double for every neighbour) on real and
// synthetic DEMs: every direction byte equal.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <queue>
#include <random>
#include <sstream>
#include <tuple>

#include <unistd.h>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/least_cost_routing.hpp"
#include "drainage/radix_heap.hpp"
#include "input/dem_reader.hpp"
#include "support/synthetic_terrain.hpp"

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


// The search as first written, kept as the reference the optimised one must match byte for byte:
// the rules of least_cost_routing.hpp in their plainest form.
std::vector<std::uint8_t> reference_least_cost(const std::vector<float>& z, const GridShape& g, double dx,
                                               double dy) {
    enum : std::uint8_t { fresh = 0, queued = 1, worked = 2, nodata = 3 };
    constexpr int visit_order[8] = {2, 6, 4, 0, 7, 3, 1, 5};  // S, N, W, E, NE, SW, SE, NW
    double dist[8];
    for (int k = 0; k < 8; ++k) dist[k] = d8_dc[k] && d8_dr[k] ? std::hypot(dx, dy) : d8_dc[k] ? dx : dy;
    std::vector<std::uint8_t> state(g.size()), dir(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i) state[i] = g.valid[i] ? fresh : nodata;
    using Item = std::tuple<std::uint32_t, std::uint32_t, std::size_t>;  // elevation key, counter, cell
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    std::uint32_t counter = 0;
    auto push = [&](std::size_t i) { queue.emplace(float_order_key(z[i]), counter++, i); };
    auto on_grid = [&](int r, int c) { return r >= 0 && r < g.rows && c >= 0 && c < g.cols; };
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (state[i] == fresh && is_boundary_cell(g, c, r)) state[i] = queued, push(i);
        }
    while (!queue.empty()) {
        const std::size_t i = std::get<2>(queue.top());
        queue.pop();
        state[i] = worked;
        const int r = int(i / std::size_t(g.cols)), c = int(i % std::size_t(g.cols));
        double slope[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
        std::size_t nb[8] = {};
        for (const int k : visit_order) {
            if (!on_grid(r + d8_dr[k], c + d8_dc[k])) continue;
            const std::size_t n = std::size_t(r + d8_dr[k]) * g.cols + std::size_t(c + d8_dc[k]);
            nb[k] = n;
            if (state[n] >= worked) continue;
            slope[k] = z[n] > z[i] ? (double(z[n]) - z[i]) / dist[k] : 0.0;
            if (state[n] == queued && dir[n]) continue;
            bool biased = false;
            if (d8_dc[k] && d8_dr[k] && slope[k] > 0)
                for (const int o : {(k + 7) & 7, (k + 1) & 7}) {
                    if (slope[o] < 0) continue;
                    const double spacing = d8_dc[o] ? dy : dx;
                    const double rise = z[n] > z[nb[o]] ? (double(z[n]) - z[nb[o]]) / spacing : 0.0;
                    biased |= slope[k] < rise;
                }
            if (biased) continue;
            const std::uint8_t toward = std::uint8_t(1u << ((k + 4) & 7));
            if (state[n] == queued) {
                if (slope[k] > 0) dir[n] = toward;
                continue;
            }
            state[n] = queued, dir[n] = toward, push(n);
        }
    }
    return dir;
}

void expect_same_as_reference(const std::vector<float>& z, const GridShape& g, double dx, double dy,
                              const char* what) {
    const std::vector<std::uint8_t> want = reference_least_cost(z, g, dx, dy);
    const std::vector<std::uint8_t> got = least_cost_directions(z, g, dx, dy);
    ASSERT_EQ(got.size(), want.size()) << what;
    std::size_t differ = 0, first = got.size();
    for (std::size_t i = 0; i < got.size(); ++i)
        if (got[i] != want[i]) first = std::min(first, i), ++differ;
    EXPECT_EQ(differ, 0u) << what << ": first at cell " << first;
    EXPECT_GT(std::count_if(want.begin(), want.end(), [](std::uint8_t d) { return d != 0; }), 0) << what;
}

void expect_same_as_reference(const DrainageGrid& g, const char* what) {
    expect_same_as_reference(g.z, GridShape{g.cols, g.rows, g.valid.data()}, g.dx, g.dy, what);
}

// Elevations rounded to whole metres (long runs of exactly equal keys: ties broken by insertion
// order), pits (the search pushes below its level), nodata holes and exact zeros of both signs,
// on a non-square grid with unequal spacing (the diagonal check's two spacings differ).
DrainageGrid quantised_holed_terrain(int cols, int rows, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-3.0f, 3.0f);
    std::vector<float> z(std::size_t(cols) * rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const float h = 20.0f * std::sin(c * 0.05f) * std::cos(r * 0.07f) + 0.1f * (r + c) + noise(rng);
            z[std::size_t(r) * cols + c] = std::round(h);
        }
    for (std::size_t i = 0; i < z.size(); i += 37) z[i] = (i / 37) % 2 ? -0.0f : 0.0f;
    DrainageGrid g = make_regular_grid(cols, rows, 1.0, std::move(z));
    g.dx = 1.0, g.dy = 1.5;
    std::uniform_int_distribution<int> pick_c(0, cols - 1), pick_r(0, rows - 1);
    for (int hole = 0; hole < 12; ++hole) {
        const int c0 = pick_c(rng), r0 = pick_r(rng), size = 1 + hole % 5;
        for (int r = r0; r < std::min(rows, r0 + size); ++r)
            for (int c = c0; c < std::min(cols, c0 + size); ++c) g.valid[std::size_t(r) * cols + c] = 0;
    }
    return g;
}

TEST(LeastCostRouting, SameDirectionsAsTheReferenceOnRealDems) {
    const Terrain volcano = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    expect_same_as_reference(resample_pn(volcano, 1), "volcano factor 1");
    expect_same_as_reference(resample_pn(volcano, 3), "volcano factor 3");
    const Terrain jacksboro = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    expect_same_as_reference(resample_pn(jacksboro, 1), "jacksboro factor 1");
    expect_same_as_reference(resample_pn(jacksboro, 2), "jacksboro factor 2");
    expect_same_as_reference(resample_pn(holed_hills(), 2), "holed hills factor 2");
}

TEST(LeastCostRouting, SameDirectionsAsTheReferenceOnQuantisedHoledTerrain) {
    for (const std::uint32_t seed : {1u, 2u, 3u}) {
        const DrainageGrid g = quantised_holed_terrain(157 + int(seed), 93, seed);
        expect_same_as_reference(g, "quantised holed terrain");
    }
    const DrainageGrid column = quantised_holed_terrain(1, 40, 4), row = quantised_holed_terrain(40, 1, 5);
    expect_same_as_reference(column, "one column");
    expect_same_as_reference(row, "one row");
}

// A flat plateau (every key equal: the order is insertion order alone), whole and with a hole,
// and a plateau at 5 m ringed by a 9 m rim with a 0 m notch.
TEST(LeastCostRouting, SameDirectionsAsTheReferenceOnAFlatPlateau) {
    DrainageGrid flat = make_regular_grid(64, 48, 2.0, std::vector<float>(64 * 48, 7.0f));
    expect_same_as_reference(flat, "flat");
    for (int r = 20; r < 26; ++r)
        for (int c = 30; c < 41; ++c) flat.valid[std::size_t(r) * 64 + c] = 0;
    expect_same_as_reference(flat, "flat with a hole");
    std::vector<float> z(50 * 40, 5.0f);
    for (int r = 0; r < 40; ++r)
        for (int c = 0; c < 50; ++c)
            if (r == 0 || c == 0 || r == 39 || c == 49) z[std::size_t(r) * 50 + c] = 9.0f;
    z[std::size_t(39) * 50 + 17] = 0.0f;
    expect_same_as_reference(make_regular_grid(50, 40, 1.0, std::move(z)), "rimmed plateau");
}

// FifoRadixHeap pops by (key, insertion order), like a binary heap on (key, counter), for any
// monotone sequence (no key below the last popped): few distinct keys (long ties), keys equal to
// the last popped pushed between pops, and keys spread over all 32 bits.
TEST(FifoRadixHeap, PopsLikeAHeapOnKeyThenInsertionOrder) {
    std::mt19937 rng(11);
    for (const std::uint32_t spread : {3u, 1000u, 0xffffffffu}) {
        FifoRadixHeap<std::uint32_t> heap;
        using Item = std::tuple<std::uint32_t, std::uint32_t>;  // key, counter = cell
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> ref;
        std::uint32_t counter = 0, pops = 0;
        for (int step = 0; step < 200000; ++step) {
            if (rng() % 3 || ref.empty()) {
                const std::uint32_t base = heap.last();
                const std::uint32_t key =
                    rng() % 4 == 0 ? base : base + std::uint32_t(std::min<std::uint64_t>(rng() % (std::uint64_t(spread) + 1), 0xffffffffu - base));
                heap.push(key, counter), ref.emplace(key, counter), ++counter;
            } else {
                const auto e = heap.pop();
                ASSERT_EQ(e.key, std::get<0>(ref.top())) << "pop " << pops;
                ASSERT_EQ(e.cell, std::get<1>(ref.top())) << "pop " << pops;
                ref.pop(), ++pops;
            }
        }
        while (!ref.empty()) {
            const auto e = heap.pop();
            ASSERT_EQ(e.cell, std::get<1>(ref.top()));
            ref.pop();
        }
        EXPECT_TRUE(heap.empty());
        EXPECT_GT(pops, 50000u);
    }
}

}  // namespace
}  // namespace penink
