// The shore at the sea level (surface/sea_level_contour.hpp) and the water it bounds
// (GridNodes::sea_level): on a cone island the contour is one closed loop on the closed-form
// circle; a straight coast is one open line on its closed-form shore; nodata stays nodata; no
// sea, no line; water nodes are drawn at the sea's height and land nodes as before.
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "input/grid_nodes.hpp"
#include "surface/sea_level_contour.hpp"
#include "support/synthetic_terrain.hpp"

using namespace penink;

namespace {

GridNodes with_sea(const Terrain& t, double sea, double z_scale = 1.0) {
    GridNodes n = grid_nodes(t);
    n.z_scale = z_scale;
    n.sea_level = sea;
    return n;
}

GridWindow whole(const Terrain& t) { return {0, 0, t.cols, t.rows}; }

}  // namespace

// A cone z = 100 - r / 2 (r metres from the centre) with the sea at 40 m: the shore is the circle
// r = 120. The mesh is linear on each triangle edge and r is too along the edge's direction up to
// its curvature: an edge of length h at distance R from the centre bends away from the circle by
// at most h^2 / (8 R); with h = 10 sqrt(2) (the diagonals) and R = 120 that is 0.21 m.
TEST(SeaLevelContour, ConeIslandIsOneLoopOnTheCircle) {
    const Terrain t = terrain_from_function(61, 61, 10.0, [](double x, double y) { return 100.0 - std::hypot(x, y) / 2.0; });
    const std::vector<ShoreLine> shore = sea_level_contour(with_sea(t, 40.0), whole(t));
    ASSERT_EQ(shore.size(), 1u);
    const ShoreLine& loop = shore[0];
    ASSERT_GT(loop.points.size(), 40u);
    EXPECT_EQ(loop.points.front(), loop.points.back());  // closed
    ASSERT_EQ(loop.ground.size(), loop.points.size());
    const double bend = 200.0 / (8.0 * 120.0);
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
        const glm::vec3& p = loop.points[i];
        EXPECT_NEAR(std::hypot(p.x, p.y), 120.0, bend + 1e-3) << i;
        EXPECT_EQ(p.z, 40.0f);
        EXPECT_GE(loop.ground[i], 40.0f);  // the mesh over the shore point: the land's edge rises
        EXPECT_LE(loop.ground[i], 40.0f + 5.0f * std::sqrt(2.0f) + 1e-3f);  // by at most one edge's rise
    }
}

// A straight coast z = x / 10 (sea at x < 0), exaggeration 3, sea at 0: one open line along
// x = 0 from the north edge to the south edge; linear along every edge, so exact to float rounding.
TEST(SeaLevelContour, StraightCoastIsOneOpenLine) {
    const Terrain t = terrain_from_function(21, 11, 5.0, [](double x, double) { return x / 10.0 + 0.25; });
    const std::vector<ShoreLine> shore = sea_level_contour(with_sea(t, 0.25, 3.0), whole(t));
    ASSERT_EQ(shore.size(), 1u);
    const ShoreLine& line = shore[0];
    EXPECT_NE(line.points.front(), line.points.back());
    EXPECT_NEAR(std::abs(line.points.front().y - line.points.back().y), 50.0, 1e-4);  // edge to edge
    for (const glm::vec3& p : line.points) {
        EXPECT_NEAR(p.x, 0.0, 1e-4);
        EXPECT_FLOAT_EQ(p.z, float(0.25 * 3.0));  // the water surface, drawn
    }
}

TEST(SeaLevelContour, NoSeaNoLineAndNodataStaysNodata) {
    Terrain t = terrain_from_function(21, 21, 5.0, [](double x, double) { return x; });
    EXPECT_TRUE(sea_level_contour(grid_nodes(t), whole(t)).empty());
    EXPECT_TRUE(sea_level_contour(with_sea(t, -1000.0), whole(t)).empty());  // all land
    EXPECT_TRUE(sea_level_contour(with_sea(t, 1000.0), whole(t)).empty());   // all water
    // A column of nodata along the coast: no triangle touching it exists, so neither does a shore on it.
    for (int r = 0; r < t.rows; ++r) t.valid[t.index(10, r)] = 0;
    const double x10 = t.pos[t.index(10, 0)].x;
    const std::vector<ShoreLine> cut = sea_level_contour(with_sea(t, x10), whole(t));
    EXPECT_TRUE(cut.empty());  // the shore x = x10 runs through the nodata nodes only
    const GridNodes n = with_sea(t, x10 + 7.0);  // x = 7: between the columns at 5 and 10 m
    const std::vector<ShoreLine> east = sea_level_contour(n, whole(t));
    ASSERT_EQ(east.size(), 1u);
    for (const glm::vec3& p : east[0].points) EXPECT_NEAR(p.x, x10 + 7.0, 1e-4);
    EXPECT_EQ(n.valid[t.index(10, 3)], 0);
}

// The water surface: nodes at or below the sea are drawn at it (times the exaggeration), others as
// before; the stored heights are untouched.
TEST(SeaLevelContour, WaterIsFlatAtTheSeaLevel) {
    const Terrain t = terrain_from_function(11, 11, 5.0, [](double x, double y) { return x + 0.5 * y; });
    const GridNodes n = with_sea(t, 2.0, 1.5);
    for (std::size_t i = 0; i < n.size(); ++i) {
        const float drawn = float(double(t.pos[i].z) * 1.5);
        EXPECT_EQ(n.at(i).z, drawn > n.sea_z() ? drawn : float(2.0 * 1.5)) << i;
        EXPECT_EQ(n.at(i).x, t.pos[i].x);
    }
    GridNodes dry = grid_nodes(t);
    dry.z_scale = 1.5;
    EXPECT_FALSE(dry.has_sea());
    for (std::size_t i = 0; i < n.size(); ++i) EXPECT_EQ(dry.at(i).z, float(double(t.pos[i].z) * 1.5));
}
