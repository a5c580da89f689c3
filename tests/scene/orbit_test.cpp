// The orbit of `penink batch --orbit N` (scene/orbit.hpp): N cameras 360/N degrees apart
// clockwise about the vertical through the point the first camera looks at, each at the same
// distance and height from it and looking at it, with the model's box inside its depth range.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "scene/orbit.hpp"

using namespace penink;

TEST(Orbit, TurnsAboutThePointLookedAt) {
    const glm::dvec3 lo{-1, -2, 0}, hi{3, 2, 2};
    Camera start;
    start.eye = {1, -10, 5};
    start.azimuth = 10, start.altitude = -20;
    const std::vector<Camera> cams = orbit_cameras(start, lo, hi, 4);
    ASSERT_EQ(cams.size(), 4u);
    // The point looked at: on the first view ray, nearest the box centre.
    const glm::dvec3 d0 = direction_from_angles(start.azimuth, start.altitude), c = 0.5 * (lo + hi);
    const glm::dvec3 p = start.eye + glm::dot(c - start.eye, d0) * d0;
    const double r0 = std::hypot(start.eye.x - p.x, start.eye.y - p.y);
    for (int k = 0; k < 4; ++k) {
        const Camera& cam = cams[std::size_t(k)];
        EXPECT_NEAR(cam.azimuth, std::fmod(10.0 + 90.0 * k, 360.0), 1e-9) << k;
        EXPECT_DOUBLE_EQ(cam.altitude, start.altitude);
        EXPECT_DOUBLE_EQ(cam.eye.z, start.eye.z);
        EXPECT_NEAR(std::hypot(cam.eye.x - p.x, cam.eye.y - p.y), r0, 1e-9) << k;
        // Its view ray passes through p (distance from p to the ray; 1e-9 of a 10-unit orbit).
        const glm::dvec3 d = direction_from_angles(cam.azimuth, cam.altitude), v = p - cam.eye;
        EXPECT_NEAR(glm::length(v - glm::dot(v, d) * d), 0.0, 1e-9) << k;
        // Every box corner lies within near..far.
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 q{i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
            const double depth = glm::dot(q - cam.eye, d);
            EXPECT_GE(depth, cam.near_plane) << k;
            EXPECT_LE(depth, cam.far_plane) << k;
        }
    }
    // Clockwise seen from above: a quarter turn takes the eye from the south of p to its west.
    const glm::dvec3 e0 = start.eye - p, e1 = cams[1].eye - p;
    EXPECT_LT(e0.x * e1.y - e0.y * e1.x, 0.0);
    EXPECT_EQ(orbit_cameras(start, lo, hi, 1).size(), 1u);
    EXPECT_EQ(orbit_cameras(start, lo, hi, 1)[0].eye, start.eye);
}
