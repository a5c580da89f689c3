// Star-like clusters of short strokes (lines/short_stroke_clusters.hpp).
#include <cmath>

#include <gtest/gtest.h>

#include "lines/short_stroke_clusters.hpp"

using namespace penink;

namespace {

// A straight stroke from `from`, `length` px along `angle_deg`, with a strength.
Stroke ray(glm::vec2 from, float angle_deg, float length, float strength) {
    const float a = angle_deg * 3.14159265f / 180.0f;
    Stroke s;
    s.points = {from, from + 0.5f * length * glm::vec2(std::cos(a), std::sin(a)), from + length * glm::vec2(std::cos(a), std::sin(a))};
    s.strength = strength;
    return s;
}

}  // namespace

// Five 12 px stubs radiating from points within 3 px of (50, 50) (a star); two stubs meeting at
// (150, 50) (a junction); a 40 px stroke from (52, 50) (not short: neither dropped nor counted);
// a lone stub. The star keeps its strongest stub alone; everything else stays.
TEST(ShortStrokeClusters, AStarKeepsItsStrongestStub) {
    std::vector<Stroke> s;
    for (int k = 0; k < 5; ++k)
        s.push_back(ray(glm::vec2(50.0f + float(k % 2) * 2.0f, 50.0f + float(k / 2)), 72.0f * float(k), 12.0f, 0.1f * float(k + 1)));
    s.push_back(ray({150, 50}, 0, 12, 0.9f));
    s.push_back(ray({150, 50}, 120, 12, 0.8f));
    s.push_back(ray({52, 50}, 10, 40, 0.05f));
    s.push_back(ray({300, 300}, 45, 10, 0.3f));
    EXPECT_EQ(count_star_clusters(s, 16.0f, 6.0f), 1u);
    const std::vector<Stroke> out = thin_star_clusters(s, 16.0f, 6.0f);
    ASSERT_EQ(out.size(), s.size() - 4);
    EXPECT_FLOAT_EQ(out[0].strength, 0.5f);  // the star's strongest
    for (std::size_t i = 1; i < out.size(); ++i) EXPECT_EQ(out[i].points, s[i + 4].points);  // the rest, in order
    EXPECT_EQ(count_star_clusters(out, 16.0f, 6.0f), 0u);
    // stubs under the radius apart only count when short: with short_px 10 none is short
    EXPECT_EQ(count_star_clusters(s, 10.0f, 6.0f), 0u);
    EXPECT_EQ(thin_star_clusters(s, 10.0f, 6.0f).size(), s.size());
}
