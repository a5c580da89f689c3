// Branches (runs between sources/junctions and the next junction/outlet) with links, and divides
// between basins, on hand grids.
#include <cmath>

#include <gtest/gtest.h>

#include "drainage/branches.hpp"
#include "drainage/drainage_build.hpp"

namespace penink {
namespace {

TEST(Branches, TreeSplitsAtJunctions) {
    DrainageGrid g = make_regular_grid(5, 3, 10.0, std::vector<float>(15, 0.0f));
    for (int i = 0; i < 15; ++i) g.z[i] = float(i);
    const std::vector<std::uint8_t> dir{2, 4, 8, 2, 4, 1, 4, 8, 2, 4, 1, 1, 1, 1, 0};
    const GridShape s{5, 3, g.valid.data()};
    FlowNetwork net;
    accumulate_flow(dir, s, net);
    label_basins(dir, s, net);
    DrainageDb db;
    build_branches(g, dir, net, db);
    // heads: 9 sources + junctions at cells 6, 9, 11, 14, in row-major order
    ASSERT_EQ(db.branches.size(), 13u);
    const std::vector<std::uint32_t> counts{2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 4, 1};
    for (std::size_t b = 0; b < 13; ++b) EXPECT_EQ(db.branches[b].count, counts[b]) << b;
    // every point once, plus one repeated junction vertex per branch that ends at a junction
    EXPECT_EQ(db.vertices.size(), 15u + 12u);
    const DvBranch& trunk = db.branches[11];  // head cell 11 -> 12 -> 13 -> outlet 14
    EXPECT_EQ(trunk.order, 2);
    EXPECT_EQ(trunk.downstream, 12);
    EXPECT_EQ(trunk.up_count, 3u);  // from J1 (cell 6), cell 7 and cell 10
    const DvBranch& outlet = db.branches[12];
    EXPECT_EQ(outlet.downstream, -1);
    EXPECT_EQ(outlet.up_count, 3u);
    EXPECT_EQ(outlet.order, 3);
    const DvVertex& last = db.vertices[trunk.first + trunk.count - 1];
    EXPECT_FLOAT_EQ(last.x, 40.0f);
    EXPECT_FLOAT_EQ(last.y, -20.0f);
    EXPECT_FLOAT_EQ(last.z, 14.0f);
    EXPECT_FLOAT_EQ(last.flow, 1.0f);
    EXPECT_FLOAT_EQ(db.vertices[trunk.first].flow, 8.0f / 15.0f);
    std::vector<std::uint32_t> up(db.upstream.begin() + outlet.up_first,
                                  db.upstream.begin() + outlet.up_first + outlet.up_count);
    EXPECT_EQ(up, (std::vector<std::uint32_t>{8, 9, 11}));  // heads at cells 8, 9 and 11
}

// The two tracing threads (north half forward, south half backward in one array) give what one
// walk in cell order gives: on a 61 x 47 grid of hashed heights (pits, ties, many basins), branch
// b starts at the b-th head cell in row-major order, follows the directions to the next head
// (repeated as its last vertex, whose branch is `downstream`) or an outlet, and its vertices
// carry the cell's position, elevation and flow, laid out one branch after another.
TEST(Branches, TwoThreadsGiveTheSequentialWalk) {
    const int cols = 61, rows = 47;
    std::vector<float> z(std::size_t(cols) * rows);
    for (std::size_t i = 0; i < z.size(); ++i)
        z[i] = float((i * 2654435761u >> 7) % 13) + 0.05f * float(i / cols);  // terraced noise
    DrainageGrid g = make_regular_grid(cols, rows, 10.0, z);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    const GridShape s{cols, rows, g.valid.data()};
    const CellBytes indeg = inflow_counts(res.dir, s);
    std::vector<std::int64_t> branch_of(z.size(), -1);
    std::int64_t next = 0;
    for (std::size_t h = 0; h < z.size(); ++h)
        if (indeg[h] != 1) branch_of[h] = next++;
    ASSERT_EQ(std::size_t(next), db.branches.size());
    ASSERT_GT(next, 500);  // both halves hold many branches
    std::size_t first = 0;
    for (std::size_t h = 0; h < z.size(); ++h) {
        if (branch_of[h] < 0) continue;
        const DvBranch& b = db.branches[std::size_t(branch_of[h])];
        ASSERT_EQ(b.first, first) << h;
        std::size_t c = h, k = 0;
        bool at_junction = false;
        for (;; ++k) {
            const DvVertex& v = db.vertices[b.first + k];
            EXPECT_EQ(v.x, float(double(c % cols) * 10.0)) << h << " " << k;
            EXPECT_EQ(v.y, float(-double(c / cols) * 10.0)) << h << " " << k;
            EXPECT_EQ(v.z, g.z[c]) << h << " " << k;
            EXPECT_EQ(v.flow, normalised_flow(res.net, c)) << h << " " << k;
            if ((at_junction = k > 0 && indeg[c] != 1)) break;  // the end junction
            if (!res.dir[c]) break;             // an outlet
            c = d8_target(s, c, res.dir[c]);
        }
        EXPECT_EQ(b.count, k + 1) << h;
        EXPECT_EQ(b.downstream, at_junction ? branch_of[c] : -1) << h;
        first += b.count;
    }
    EXPECT_EQ(first, db.vertices.size());
}

TEST(Divides, RidgeBetweenTwoBasins) {
    DrainageGrid g = make_regular_grid(5, 3, 1.0, {3, 4, 5, 4, 3, 2, 3, 4, 3, 2, 3, 4, 5, 4, 3});
    DrainageResult res;
    DrainageDb db = drainage_db_from_grid(g, {}, &res);
    EXPECT_EQ(res.stats.basins, 2u);
    ASSERT_EQ(db.divides.size(), 1u);
    ASSERT_EQ(db.divides[0].count, 5u);
    // corners (2,0) (2,1) (2,2) (3,2) (3,3): between points, clamped to the grid at the border
    const std::vector<std::pair<float, float>> xy{
        {1.5f, 0.0f}, {1.5f, -0.5f}, {1.5f, -1.5f}, {2.5f, -1.5f}, {2.5f, -2.0f}};
    for (std::size_t k = 0; k < 5; ++k) {
        EXPECT_FLOAT_EQ(db.divide_vertices[k].x, xy[k].first) << k;
        EXPECT_FLOAT_EQ(db.divide_vertices[k].y, xy[k].second) << k;
        EXPECT_EQ(db.divide_vertices[k].flow, 0.0f);
    }
    EXPECT_FLOAT_EQ(db.divide_vertices[0].z, 5.0f);  // higher of points (1,0) and (2,0)
    EXPECT_FLOAT_EQ(db.divide_vertices[2].z, 5.0f);  // max of (1,1) (2,1) (1,2) (2,2)
}

TEST(Divides, SegmentsMatchBasinBoundaries) {
    // a 7x7 pyramid pit around a nodata hole: the 8 cells around the hole are outlets (basins),
    // divides radiate between them.
    std::vector<float> z(49, 10.0f);
    std::vector<std::uint8_t> valid(49, 1);
    valid[24] = 0;
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) z[r * 7 + c] = float(std::max(std::abs(r - 3), std::abs(c - 3)));
    DrainageGrid g = make_regular_grid(7, 7, 1.0, z, valid);
    DrainageDb db = drainage_db_from_grid(g);
    std::size_t segments = 0;
    for (const DvPolyline& p : db.divides) segments += p.count - 1;
    // each divide segment separates two valid 4-neighbours of different basins
    std::size_t pairs = 0;
    DrainageResult res;
    DrainageGrid g2 = make_regular_grid(7, 7, 1.0, z, valid);
    drainage_db_from_grid(g2, {}, &res);
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) {
            const int i = r * 7 + c;
            if (!valid[i]) continue;
            if (c + 1 < 7 && valid[i + 1] && res.net.basin[i] != res.net.basin[i + 1]) ++pairs;
            if (r + 1 < 7 && valid[i + 7] && res.net.basin[i] != res.net.basin[i + 7]) ++pairs;
        }
    EXPECT_EQ(segments, pairs);
    EXPECT_GT(pairs, 0u);
}


TEST(Divides, SegmentsMatchBasinBoundariesOnAWideGrid) {
    // rows of 150 cells (the corner scan goes 64 at a time), many basins draining to the border
    const int cols = 150, rows = 40;
    std::vector<float> z(std::size_t(cols) * rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            z[std::size_t(r) * cols + c] = float(5.0 + 3.0 * std::sin(0.37 * c) + 2.0 * std::cos(0.23 * r + 0.11 * c) +
                                                 0.01 * ((c * 7919 + r * 104729) % 13));
    DrainageResult res;
    DrainageGrid g = make_regular_grid(cols, rows, 1.0, z, {});
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    std::size_t segments = 0, pairs = 0;
    for (const DvPolyline& p : db.divides) segments += p.count - 1;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const std::size_t i = std::size_t(r) * cols + c;
            if (c + 1 < cols && res.net.basin[i] != res.net.basin[i + 1]) ++pairs;
            if (r + 1 < rows && res.net.basin[i] != res.net.basin[i + cols]) ++pairs;
        }
    EXPECT_EQ(segments, pairs);
    EXPECT_GT(pairs, 100u);
}

}  // namespace
}  // namespace penink
