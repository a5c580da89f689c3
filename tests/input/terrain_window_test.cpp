#include "input/terrain_window.hpp"

#include <algorithm>

#include <gtest/gtest.h>
#include <glm/vec4.hpp>

#include "core/camera.hpp"

namespace penink {
namespace {

// Flat n x n grid, `cell` metres apart, centred on the origin, row 0 north.
Terrain flat_grid(int n, double cell) {
    Terrain t;
    t.cols = t.rows = n;
    const double half = (n - 1) * cell / 2;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) t.pos.emplace_back(c * cell - half, half - r * cell, 0.0f);
    t.valid.assign(t.size(), 1);
    return t;
}

bool inside(const glm::dmat4& vp, const glm::vec3& p) {
    const glm::dvec4 c = vp * glm::dvec4(glm::dvec3(p), 1.0);
    return c.w > 0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
}

// Brute-force node bounds of the nodes inside the frustum.
GridWindow visible_nodes(const Terrain& t, const glm::dmat4& vp) {
    GridWindow w{t.cols, t.rows, 0, 0};
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c)
            if (inside(vp, t.pos[t.index(c, r)]))
                w = {std::min(w.c0, c), std::min(w.r0, r), std::max(w.c1, c + 1), std::max(w.r1, r + 1)};
    return w;
}

TEST(TerrainWindow, WholeGridInViewKeepsEverything) {
    const Terrain t = flat_grid(101, 10);
    glm::dvec3 lo, hi;
    ASSERT_TRUE(terrain_bounds(t, lo, hi));
    const Camera cam = frame_box(lo, hi, {.azimuth = 225, .altitude = -40, .fov = 40, .width = 1000, .height = 750});
    const GridWindow w = visible_window(t, view_projection(cam), 0);
    EXPECT_EQ(w.c0, 0);
    EXPECT_EQ(w.r0, 0);
    EXPECT_EQ(w.c1, 101);
    EXPECT_EQ(w.r1, 101);
}

TEST(TerrainWindow, CameraOnTheNorthEastQuarterKeepsAboutAQuarter) {
    const Terrain t = flat_grid(101, 10);  // x, y in -500..500
    const Camera cam = frame_box({0, 0, 0}, {500, 500, 0}, {.azimuth = 0, .altitude = -90, .fov = 40, .width = 800, .height = 800});
    const glm::dmat4 vp = view_projection(cam);
    const GridWindow seen = visible_nodes(t, vp);
    ASSERT_GT(seen.cols(), 40);
    const GridWindow w = visible_window(t, vp, 0);
    // Straddling cells add at most two nodes on each open side; the grid clamps the others.
    EXPECT_EQ(w.c1, 101);
    EXPECT_EQ(w.r0, 0);
    EXPECT_LE(w.c0, seen.c0 - 1);
    EXPECT_GE(w.c0, seen.c0 - 2);
    EXPECT_GE(w.r1, seen.r1 + 1);
    EXPECT_LE(w.r1, seen.r1 + 2);
    EXPECT_LT(w.cols(), 60);
    EXPECT_LT(w.rows(), 60);
    const GridWindow m = visible_window(t, vp, 3);
    EXPECT_EQ(m.c0, w.c0 - 3);
    EXPECT_EQ(m.r1, w.r1 + 3);
    EXPECT_EQ(m.c1, 101);
    EXPECT_EQ(m.r0, 0);
}

TEST(TerrainWindow, LookingAwayIsEmpty) {
    const Terrain t = flat_grid(21, 10);
    Camera cam;
    cam.eye = {-500, 0, 50};
    cam.azimuth = 270, cam.altitude = 10;  // west, away from the grid
    EXPECT_EQ(visible_window(t, view_projection(cam), 5).cols(), 0);
}

TEST(TerrainWindow, CellStraddlingTheViewIsKeptThoughNoNodeIsInside) {
    const Terrain t = flat_grid(2, 10000);  // one 10 km cell
    Camera cam;
    cam.eye = {0, 0, 100};
    cam.azimuth = 0, cam.altitude = -90;
    const glm::dmat4 vp = view_projection(cam);
    EXPECT_EQ(visible_nodes(t, vp).cols(), -2);  // no node inside
    const GridWindow w = visible_window(t, vp, 0);
    EXPECT_EQ(w.c0, 0);
    EXPECT_EQ(w.r0, 0);
    EXPECT_EQ(w.c1, 2);
    EXPECT_EQ(w.r1, 2);
}

TEST(TerrainWindow, InvalidNodesAreIgnored) {
    Terrain t = flat_grid(101, 10);
    const Camera cam = frame_box({0, 0, 0}, {500, 500, 0}, {.azimuth = 0, .altitude = -90, .fov = 40, .width = 800, .height = 800});
    const GridWindow full = visible_window(t, view_projection(cam), 0);
    // Invalidate the columns of the visible window's west part: the window shrinks east.
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < 70; ++c) t.valid[t.index(c, r)] = 0;
    const GridWindow w = visible_window(t, view_projection(cam), 0);
    // Column 70 is the first valid one; the straddling cell there on the south edge keeps
    // its ring of neighbour cells, hence one column more.
    EXPECT_EQ(w.c0, 69);
    EXPECT_EQ(w.c1, full.c1);
    EXPECT_EQ(w.r1, full.r1);
}

}  // namespace
}  // namespace penink
