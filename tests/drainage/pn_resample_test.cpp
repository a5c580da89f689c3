// PN resampling: factor 1 reproduces the DEM nodes exactly; a plane stays a plane at factor 3.
#include <cmath>

#include <cstring>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "drainage/dem_surface.hpp"
#include "drainage/drainage_grid.hpp"
#include "input/dem_reader.hpp"
#include "support/test_grids.hpp"

namespace penink {
namespace {

Terrain hand_terrain(int cols, int rows, double spacing, float (*height)(float, float)) {
    Terrain t;
    t.cols = cols, t.rows = rows, t.origin = {1000.0, 5000.0};
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const float x = float(c * spacing), y = float(-r * spacing);
            t.pos.emplace_back(x, y, height(x, y));
            t.valid.push_back(1);
        }
    return t;
}

float bumpy(float x, float y) { return 50.0f * std::sin(x * 0.05f) * std::cos(y * 0.07f) + 0.3f * x; }
float plane(float x, float y) { return 0.2f * x - 0.1f * y + 7.0f; }

TEST(PnResample, FactorOneReproducesNodes) {
    const Terrain t = hand_terrain(7, 5, 10.0, bumpy);
    const DrainageGrid g = resample_pn(t, 1);
    ASSERT_EQ(g.cols, 7);
    ASSERT_EQ(g.rows, 5);
    for (std::size_t i = 0; i < t.size(); ++i) {
        EXPECT_EQ(g.z[i], t.pos[i].z) << i;
        EXPECT_EQ(g.valid[i], 1);
    }
    EXPECT_DOUBLE_EQ(grid_xy(g, 6, 4).x, 60.0);
    EXPECT_DOUBLE_EQ(grid_xy(g, 6, 4).y, -40.0);
    EXPECT_DOUBLE_EQ(g.dx, 10.0);
}

TEST(PnResample, PlaneStaysPlanarAtFactorThree) {
    const Terrain t = hand_terrain(5, 4, 10.0, plane);
    const DrainageGrid g = resample_pn(t, 3);
    ASSERT_EQ(g.cols, 13);
    ASSERT_EQ(g.rows, 10);
    EXPECT_NEAR(g.dx, 10.0 / 3.0, 1e-9);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const glm::dvec2 p = grid_xy(g, c, r);
            EXPECT_NEAR(p.x, c * 10.0 / 3.0, 1e-4);
            EXPECT_NEAR(p.y, -r * 10.0 / 3.0, 1e-4);
            EXPECT_NEAR(g.z[g.index(c, r)], plane(float(p.x), float(p.y)), 1e-4) << c << "," << r;
        }
}

TEST(PnResample, NodesAtFactorMultiplesKeepElevationsAndCurvedBetween) {
    const Terrain t = hand_terrain(6, 6, 10.0, bumpy);
    const DrainageGrid g = resample_pn(t, 4);
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c)
            EXPECT_NEAR(g.z[g.index(c * 4, r * 4)], t.pos[t.index(c, r)].z, 1e-4);
    // a fine node inside a cell differs from the flat triangle (PN curvature)
    const float flat = 0.5f * (t.pos[t.index(1, 1)].z + t.pos[t.index(2, 2)].z);
    EXPECT_GT(std::abs(g.z[g.index(6, 6)] - flat), 1e-3f);
}

TEST(PnResample, MissingTriangleInvalidatesItsNodes) {
    Terrain t = hand_terrain(3, 3, 10.0, plane);
    t.valid[t.index(2, 2)] = 0;  // SE node: both triangles of cell (1,1) lose it
    const DrainageGrid g = resample_pn(t, 2);
    EXPECT_EQ(g.valid[g.index(4, 4)], 0);  // the missing node
    EXPECT_EQ(g.valid[g.index(3, 3)], 0);  // on the diagonal towards it
    EXPECT_EQ(g.valid[g.index(4, 2)], 1);  // the NE node of cell (1,1) still has data
    EXPECT_EQ(g.valid[g.index(3, 2)], 1);  // on edge a-b of the dropped triangle
    EXPECT_EQ(g.valid[g.index(2, 2)], 1);
}

TEST(PnResample, HeightsOnlyTerrainGivesTheSameGridAtFactorOne) {
    test::TempDir dir;
    const double c = std::cos(0.3), s = std::sin(0.3), nodata = -9999;
    const std::string rotated = test::write_tif(dir.file("r.tif"), 4, 3, {1, 2, 3, 4, 5, -9999, 7, 8, 9, 10, 11, 12},
                                                {1000, 10 * c, 10 * s, 5000, 10 * s, -10 * c}, 2193, &nodata);
    DemOptions heights;
    heights.heights_only = true;
    // volcano and the rotated grid are affine; jacksboro is geographic (its UTM x, y come in h.xy)
    for (const std::string& p : {std::string(PENINK_SOURCE_DIR "/examples/volcano.asc"), rotated,
                                 std::string(PENINK_SOURCE_DIR "/examples/jacksboro.tif")}) {
        const DrainageGrid full = resample_pn(read_dem(p), 1);
        Terrain h = read_dem(p, heights);
        EXPECT_THROW(resample_pn(h, 2), Error);  // positions needed between the nodes
        const DrainageGrid g = resample_pn_releasing(h, 1);
        EXPECT_TRUE(h.z.empty());
        EXPECT_TRUE(h.xy.empty());
        EXPECT_EQ(g.coarse_xy, full.coarse_xy);
        EXPECT_EQ(g.z, full.z);  // nodata nodes 0 in both
        EXPECT_EQ(g.valid, full.valid);
        EXPECT_EQ(g.dx, full.dx);  // the same floats summed in the same order
        EXPECT_EQ(g.dy, full.dy);
        for (int r = 0; r < g.rows; ++r)
            for (int col = 0; col < g.cols; ++col) ASSERT_EQ(grid_xy(g, col, r), grid_xy(full, col, r)) << p;
    }
}

// A geographic DEM's node x, y let go and made again: the same floats, and grid_xy the same
// meanwhile (from the formula); the mask taken over (the coarse one left out at factor 1). An
// affine grid's (no coarse_xy to let go) and a grid read with positions (no formula) keep theirs.
TEST(PnResample, GeographicNodeXyIsReleasedAndMadeAgainBitForBit) {
    DemOptions heights;
    heights.heights_only = true;
    Terrain h = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif", heights);
    const std::vector<std::uint8_t> mask = h.valid;
    DrainageGrid g = resample_pn_releasing(h, 1);
    ASSERT_TRUE(g.node_xy);
    EXPECT_TRUE(h.valid.empty());
    EXPECT_EQ(g.valid, mask);
    EXPECT_TRUE(g.coarse_valid.empty());
    const NodeXY xy = g.coarse_xy;
    ASSERT_EQ(xy.size(), g.size());
    ASSERT_TRUE(release_node_xy(g));
    EXPECT_EQ(g.coarse_xy.capacity(), 0u);
    for (int r = 0; r < g.rows; r += 7)
        for (int c = 0; c < g.cols; c += 5) ASSERT_EQ(grid_xy(g, c, r), glm::dvec2(xy[g.index(c, r)])) << c << " " << r;
    EXPECT_EQ(grid_xy_at(g, 10.25, 20.5), [&] {
        DrainageGrid kept = g;
        kept.coarse_xy = xy;
        return grid_xy_at(kept, 10.25, 20.5);
    }());
    restore_node_xy(g);
    EXPECT_EQ(g.coarse_xy, xy);
    restore_node_xy(g);  // there: nothing
    EXPECT_EQ(g.coarse_xy, xy);

    DrainageGrid affine = resample_pn_releasing(h = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc", heights), 1);
    EXPECT_FALSE(affine.node_xy);
    EXPECT_FALSE(release_node_xy(affine));
    DrainageGrid full = resample_pn(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 1);
    EXPECT_FALSE(full.node_xy);
    EXPECT_FALSE(release_node_xy(full));
    EXPECT_EQ(full.coarse_xy, xy);
}

// The node x, y let go and read from the rows' samples kept instead (readable_node_xy: 1 B a node,
// not 8): every node's grid_xy, points between nodes (grid_xy_at) and the draping surface's nodes
// and hits are the same floats as with coarse_xy whole; restoring coarse_xy lets the samples go.
TEST(PnResample, NodeXyReadFromRowSamplesIsCoarseXyBitForBit) {
    DemOptions heights;
    heights.heights_only = true;
    Terrain h = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif", heights);
    DrainageGrid g = resample_pn_releasing(h, 1);
    ASSERT_TRUE(g.node_xy);
    DrainageGrid kept = g;  // coarse_xy whole
    ASSERT_TRUE(release_node_xy(g));
    readable_node_xy(g);
    ASSERT_TRUE(g.xy_rows);
    EXPECT_TRUE(g.coarse_xy.empty());
    EXPECT_LT(g.xy_rows->bytes(), kept.coarse_xy.size() * sizeof(glm::vec2) / 4);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const glm::dvec2 a = grid_xy(g, c, r), b = grid_xy(kept, c, r);
            ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << c << " " << r;
        }
    for (const glm::dvec2 at : {glm::dvec2(10.25, 20.5), glm::dvec2(0.0, 0.0), glm::dvec2(401.75, 342.5), glm::dvec2(200.1, 17.9)})
        EXPECT_EQ(grid_xy_at(g, at.x, at.y), grid_xy_at(kept, at.x, at.y)) << at.x << " " << at.y;
    const DemSurface from_rows(g), from_xy(kept);
    for (int r = 0; r < g.rows; r += 3)
        for (int c = 0; c < g.cols; c += 3) {
            ASSERT_EQ(from_rows.node(c, r), from_xy.node(c, r)) << c << " " << r;
            ASSERT_EQ(from_rows.normal(c, r), from_xy.normal(c, r)) << c << " " << r;
        }
    const DemDraper d_rows(from_rows), d_xy(from_xy);
    for (int k = 0; k < 200; ++k) {
        const glm::dvec2 p = grid_xy_at(kept, 3.0 + k * 1.93, 5.0 + k * 1.61);
        int c0 = -1, r0 = -1, c1 = -1, r1 = -1;
        DemHit a, b;
        ASSERT_EQ(d_rows.locate(p.x, p.y, c0, r0, a), d_xy.locate(p.x, p.y, c1, r1, b)) << k;
        EXPECT_EQ(a.cell, b.cell) << k;
        EXPECT_EQ(a.bary, b.bary) << k;
    }
    // Drapers of surfaces whose normals are made on demand (the crease tiles'): the nodes made
    // from the rows' samples are kept in the draper's window (DemSurface::NodeXYCache) and give the
    // same hits, heights and normals along paths hinted by the point before: one wrapping over the
    // grid (more than a 64 x 64 window: slots taken over by other nodes), one down a few columns
    // (nodes 64 rows apart: one slot, its key telling them apart).
    {
        const DemSurface lazy_rows(g, DemSurface::Normals::on_demand), lazy_xy(kept, DemSurface::Normals::on_demand);
        const DemDraper l_rows(lazy_rows), l_xy(lazy_xy);
        int c0 = -1, r0 = -1, c1 = -1, r1 = -1;
        for (int k = 0; k < 4000; ++k) {
            const glm::dvec2 p = k < 2000 ? grid_xy_at(kept, 2.0 + std::fmod(k * 0.31, g.cols - 4.0), 2.0 + std::fmod(k * 0.17, g.rows - 4.0))
                                          : grid_xy_at(kept, 20.0 + 0.45 * std::sin(k * 0.7), 2.0 + std::fmod(k * 0.35, g.rows - 4.0));
            DemHit a, b;
            const bool on = l_rows.locate(p.x, p.y, c0, r0, a);
            ASSERT_EQ(on, l_xy.locate(p.x, p.y, c1, r1, b)) << k;
            if (!on) continue;
            ASSERT_EQ(a.cell, b.cell) << k;
            glm::vec3 na, nb;
            const float za = l_rows.height_normal(a, na), zb = l_xy.height_normal(b, nb);
            ASSERT_EQ(std::memcmp(&za, &zb, sizeof za), 0) << k;
            ASSERT_EQ(std::memcmp(&na, &nb, sizeof na), 0) << k;
        }
    }
    restore_node_xy(g);
    EXPECT_EQ(g.coarse_xy, kept.coarse_xy);
    EXPECT_FALSE(g.xy_rows);
}

TEST(PnResample, RejectsBadFactor) {
    Terrain t = hand_terrain(3, 3, 10.0, plane);
    t.source = "dem.tif";
    try {
        resample_pn(t, 0);
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: drainage: dem.tif: resample factor must be >= 1");
    }
}

}  // namespace
}  // namespace penink
