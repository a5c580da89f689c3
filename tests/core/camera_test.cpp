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
    const Camera c = frame_box(lo, hi, 45, -30, 40, 1000, 750, 0.9);
    glm::dvec2 mn, mx;
    box_extent(c, lo, hi, mn, mx);
    EXPECT_NEAR((mx.x - mn.x) / 1000.0, 0.9, 0.02);
    EXPECT_GT(mn.y, 0.0);
    EXPECT_LT(mx.y, 750.0);
}

TEST(Camera, FrameBoxFitsTheHeightOfATallBox) {
    const glm::dvec3 lo(-1, -1, 0), hi(1, 1, 10);  // a tower
    const Camera c = frame_box(lo, hi, 0, 0, 40, 1000, 750, 0.9);
    glm::dvec2 mn, mx;
    box_extent(c, lo, hi, mn, mx);
    EXPECT_NEAR((mx.y - mn.y) / 750.0, 0.9, 0.02);
    EXPECT_LT(mx.x - mn.x, 900.0);
}
