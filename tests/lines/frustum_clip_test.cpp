// Clipping world polylines to the view frustum (Liang-Barsky in clip space).
#include <gtest/gtest.h>

#include "core/camera.hpp"
#include "lines/frustum_clip.hpp"

using namespace penink;

namespace {

Camera looking_north() {
    Camera c;
    c.eye = {0, 0, 0}, c.azimuth = 0, c.altitude = 0, c.fov = 90;
    c.width = 100, c.height = 100, c.near_plane = 1, c.far_plane = 1000;
    return c;
}

}  // namespace

TEST(FrustumClip, InsideLineUnchanged) {
    const Camera c = looking_north();
    const std::vector<std::vector<glm::vec3>> in = {{{-1, 10, 0}, {1, 10, 0}, {1, 20, 0}}};
    const auto out = clip_polylines_to_frustum(in, view_projection(c), 0.0);
    ASSERT_EQ(out.size(), 1u);
    ASSERT_EQ(out[0].size(), 3u);
    EXPECT_EQ(out[0][2], glm::vec3(1, 20, 0));
}

TEST(FrustumClip, SegmentThroughTheEyePlaneIsCutAtNear) {
    const Camera c = looking_north();
    // From 50 m behind the eye to 50 m in front, along the view axis.
    const auto out = clip_polylines_to_frustum({{{0, -50, 0}, {0, 50, 0}}}, view_projection(c), 0.0);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(out[0][0].y, 1.0, 1e-3);  // the near plane
    EXPECT_NEAR(out[0][1].y, 50.0, 1e-4);
}

TEST(FrustumClip, LineLeavingAndReenteringIsSplit) {
    const Camera c = looking_north();  // 90 degree fov: inside while |x| <= y
    const std::vector<std::vector<glm::vec3>> in = {{{0, 10, 0}, {30, 10, 0}, {30, 100, 0}, {0, 100, 0}}};
    const auto out = clip_polylines_to_frustum(in, view_projection(c), 0.0);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_NEAR(out[0].back().x, 10.0, 1e-3);  // leaves through x = y at (10, 10)
    EXPECT_NEAR(out[1].front().y, 30.0, 1e-3);  // re-enters at (30, 30)
    EXPECT_EQ(out[1].back(), glm::vec3(0, 100, 0));
}

TEST(FrustumClip, OutsideLineDropped) {
    const Camera c = looking_north();
    EXPECT_TRUE(clip_polylines_to_frustum({{{0, -10, 0}, {5, -20, 0}}}, view_projection(c)).empty());
}
