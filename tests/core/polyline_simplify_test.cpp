#include "core/polyline_simplify.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace penink {
namespace {

TEST(PolylineSimplify, DouglasPeuckerKnownAnswer) {
    // Classic example: deviations 0.1 (i=1), 3 (i=3), 0.2 (i=2, 4) from the chords.
    std::vector<glm::vec2> p = {{0, 0}, {1, 0.1f}, {2, -0.1f}, {3, 5}, {4, 6}, {5, 7}, {6, 8.1f}, {7, 9}};
    EXPECT_EQ(douglas_peucker_indices(p, 0.5f), (std::vector<std::size_t>{0, 2, 3, 7}));
    EXPECT_EQ(douglas_peucker_indices(p, 10.0f), (std::vector<std::size_t>{0, 7}));
    std::vector<glm::vec2> line = {{0, 0}, {1, 1}, {2, 2}, {3, 0}};
    EXPECT_EQ(douglas_peucker_indices(line, 0.0f), (std::vector<std::size_t>{0, 2, 3}));
}

TEST(PolylineSimplify, PointSegmentDistance) {
    EXPECT_FLOAT_EQ(point_segment_distance({5, 3}, {0, 0}, {10, 0}), 3.0f);
    EXPECT_FLOAT_EQ(point_segment_distance({13, 4}, {0, 0}, {10, 0}), 5.0f);
    EXPECT_FLOAT_EQ(point_segment_distance({3, 4}, {0, 0}, {0, 0}), 5.0f);
}

// A straight line whose value rises as 1 - (1 - u)^2 over its first 10 px (a taper) and stays 1:
// the points kept hold the value within value_tol everywhere (linear in arc length between
// them), a few along the curve and none along the flat part; without values, the two ends.
TEST(PolylineSimplify, ValuesKeptWithinTheirTolerance) {
    std::vector<glm::vec2> p;
    std::vector<float> v;
    for (int i = 0; i <= 40; ++i) {
        p.push_back(glm::vec2(0.5f * float(i), 0.0f));
        const float u = std::min(1.0f, 0.5f * float(i) / 10.0f);
        v.push_back(1.0f - (1.0f - u) * (1.0f - u));
    }
    EXPECT_EQ(douglas_peucker_indices(p, 0.05f), (std::vector<std::size_t>{0, 40}));
    const std::vector<std::size_t> k = douglas_peucker_indices(p, 0.05f, v, 0.02f);
    ASSERT_GE(k.size(), 4u);
    EXPECT_LE(k.size(), 8u);  // the curve's chord error 1/4 (h / 10)^2 <= 0.02 needs h >= 2.8 px: 4 chords
    EXPECT_EQ(k.front(), 0u);
    EXPECT_EQ(k.back(), 40u);
    for (std::size_t j = 0; j + 1 < k.size(); ++j)
        for (std::size_t i = k[j]; i <= k[j + 1]; ++i) {
            const float f = float(i - k[j]) / float(k[j + 1] - k[j]);
            EXPECT_NEAR(v[k[j]] + f * (v[k[j + 1]] - v[k[j]]), v[i], 0.02f + 1e-6f) << i;
        }
}

TEST(PolylineSimplify, RingKeepsItsCorners) {
    std::vector<glm::vec2> ring;  // a 10 x 10 square with points every unit
    for (int k = 0; k < 40; ++k)
        ring.push_back(k < 10 ? glm::vec2(k, 0) : k < 20 ? glm::vec2(10, k - 10) : k < 30 ? glm::vec2(30 - k, 10) : glm::vec2(0, 40 - k));
    EXPECT_EQ(douglas_peucker_ring_indices(ring, 0.1f), (std::vector<std::size_t>{0, 10, 20, 30}));
    EXPECT_EQ(douglas_peucker_ring_indices(ring, 100.0f).size(), 3u);  // never below a triangle
}

}  // namespace
}  // namespace penink
