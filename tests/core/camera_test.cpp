// Camera maths: view directions from azimuth/altitude, projection to pixels, and framing a box
// (by width, or by height for a tall box).
#include <cmath>

#include <gtest/gtest.h>

#include "core/camera.hpp"

using namespace penink;

TEST(Camera, DirectionFromAngles) {
    const glm::dvec3 north = direction_from_angles(0, 0), east = direction_from_angles(90, 0);
    EXPECT_NEAR(north.y, 1.0, 1e-12);
    EXPECT_NEAR(east.x, 1.0, 1e-12);
    const glm::dvec3 down = direction_from_angles(45, -30);
    EXPECT_NEAR(down.z, -0.5, 1e-12);
    EXPECT_NEAR(down.x, down.y, 1e-12);
    EXPECT_NEAR(light_vector(Light{315, 90}).z, 1.0, 1e-12);
}

TEST(Camera, ProjectsTheViewCentreToTheImageCentre) {
    Camera c;
    c.eye = {100, 200, 50}, c.azimuth = 30, c.altitude = -20, c.width = 640, c.height = 480;
    const glm::dvec3 p = c.eye + direction_from_angles(30, -20) * 250.0;
    glm::dvec2 px;
    double depth = 0;
    ASSERT_TRUE(project_to_pixel(c, p, px, depth));
    EXPECT_NEAR(px.x, 320.0, 1e-6);
    EXPECT_NEAR(px.y, 240.0, 1e-6);
    EXPECT_NEAR(depth, 250.0, 1e-9);
    EXPECT_FALSE(project_to_pixel(c, c.eye - direction_from_angles(30, -20), px, depth));  // behind
}

namespace {

// Projected extent of the box corners, pixels.
void box_extent(const Camera& c, glm::dvec3 lo, glm::dvec3 hi, glm::dvec2& min, glm::dvec2& max) {
    min = glm::dvec2(1e300), max = glm::dvec2(-1e300);
    for (int i = 0; i < 8; ++i) {
        glm::dvec2 px;
        double d;
        ASSERT_TRUE(project_to_pixel(c, {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z}, px, d));
        min = glm::min(min, px), max = glm::max(max, px);
    }
}

}  // namespace

TEST(Camera, FrameBoxFillsTheWidthOfAFlatBox) {
    const glm::dvec3 lo(0, 0, 0), hi(1000, 800, 50);
    const Camera c = frame_box(lo, hi, {.azimuth = 45, .altitude = -30, .fov = 40, .width = 1000, .height = 750, .fill = 0.9});
    glm::dvec2 mn, mx;
    box_extent(c, lo, hi, mn, mx);
    EXPECT_NEAR((mx.x - mn.x) / 1000.0, 0.9, 0.02);
    EXPECT_GT(mn.y, 0.0);
    EXPECT_LT(mx.y, 750.0);
}

TEST(Camera, FrameBoxFitsTheHeightOfATallBox) {
    const glm::dvec3 lo(-1, -1, 0), hi(1, 1, 10);  // a tower
    const Camera c = frame_box(lo, hi, {.azimuth = 0, .altitude = 0, .fov = 40, .width = 1000, .height = 750, .fill = 0.9});
    glm::dvec2 mn, mx;
    box_extent(c, lo, hi, mn, mx);
    EXPECT_NEAR((mx.y - mn.y) / 750.0, 0.9, 0.02);
    EXPECT_LT(mx.x - mn.x, 900.0);
}

// Orthographic: the image spans view_width world units at any depth, depth is the distance along
// the view direction, and framing puts every point in front of the eye plane and inside the image.
TEST(Camera, OrthographicProjectsByViewWidthAndDepthAlongTheViewDirection) {
    const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1000, 0, 50}, {0, 500, 120}, {1000, 500, 10}};
    const Camera c = frame_points_orthographic(pts, {.azimuth = 0.0, .altitude = -90.0, .width = 800, .height = 400, .view_width = 1250.0});
    ASSERT_TRUE(is_orthographic(c));
    EXPECT_DOUBLE_EQ(c.view_width, 1250.0);
    EXPECT_DOUBLE_EQ(world_per_pixel(c, 1.0), 1250.0 / 800.0);
    EXPECT_DOUBLE_EQ(world_per_pixel(c, 1e6), 1250.0 / 800.0);
    glm::dvec2 a, b;
    double da = 0, db = 0;
    ASSERT_TRUE(project_to_pixel(c, {0, 0, 0}, a, da));
    ASSERT_TRUE(project_to_pixel(c, {1000, 500, 120}, b, db));
    // Plan view, north up: x east goes right, y north goes up; 1000 m = 640 px, 500 m = 320 px.
    EXPECT_NEAR(b.x - a.x, 640.0, 1e-6);
    EXPECT_NEAR(a.y - b.y, 320.0, 1e-6);
    EXPECT_NEAR((a.x + b.x) * 0.5, 400.0, 1e-6);  // centred
    EXPECT_NEAR((a.y + b.y) * 0.5, 200.0, 1e-6);
    EXPECT_NEAR(da - db, 120.0, 1e-6);  // looking down: the higher point is 120 m nearer
    EXPECT_NEAR(eye_depth(c, {0, 0, 0}), da, 1e-6);
    EXPECT_GT(db, 0.0);
    EXPECT_GT(db, c.near_plane);
    EXPECT_LT(da, c.far_plane);
    const glm::dvec3 t = toward_viewer(c, {7, 8, 9});
    EXPECT_NEAR(t.z, 1.0, 1e-12);
}

TEST(Camera, OrthographicFramingFitsTheTighterSide) {
    // An oblique orthographic view: the points span fill of the width or height, whichever binds.
    std::vector<glm::dvec3> pts;
    for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1 ? 300.0 : 0.0, i & 2 ? 2000.0 : 0.0, i & 4 ? 100.0 : 0.0);
    const Camera c = frame_points_orthographic(pts, {.azimuth = 30.0, .altitude = -35.0, .width = 600, .height = 600, .fill = 0.8});
    double xl = 1e9, xr = -1e9, yl = 1e9, yr = -1e9;
    for (const glm::dvec3& p : pts) {
        glm::dvec2 px;
        double d = 0;
        ASSERT_TRUE(project_to_pixel(c, p, px, d));
        EXPECT_GT(d, c.near_plane);
        EXPECT_LT(d, c.far_plane);
        xl = std::min(xl, px.x), xr = std::max(xr, px.x), yl = std::min(yl, px.y), yr = std::max(yr, px.y);
    }
    EXPECT_NEAR(std::max(xr - xl, yr - yl), 480.0, 1e-6);
    EXPECT_NEAR((xl + xr) * 0.5, 300.0, 1e-6);
    EXPECT_NEAR((yl + yr) * 0.5, 300.0, 1e-6);
}
