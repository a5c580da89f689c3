#include "lines/simplify.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace penink {
namespace {

TEST(Simplify, StrokeKeepsDepthOfKeptPoints) {
    Stroke s{{{0, 0}, {1, 0.1f}, {2, 0}, {3, 0}, {3, 0}, {3, 4}}, {10, 11, 12, 13, 14, 15}, 2.0f, "crease", {}};
    Stroke r = simplify_stroke(s, 0.5f);
    EXPECT_EQ(r.points, (std::vector<glm::vec2>{{0, 0}, {3, 0}, {3, 4}}));
    EXPECT_EQ(r.depth, (std::vector<float>{10, 13, 15}));
    EXPECT_EQ(r.kind, "crease");
    EXPECT_FLOAT_EQ(r.strength, 2.0f);
}

TEST(Simplify, ClosedStrokeStaysClosed) {
    Stroke s;
    for (int i = 0; i <= 40; ++i) {  // square 10 x 10 with points every unit, closed
        int k = i % 40;
        glm::vec2 p = k < 10 ? glm::vec2(k, 0) : k < 20 ? glm::vec2(10, k - 10) : k < 30 ? glm::vec2(30 - k, 10) : glm::vec2(0, 40 - k);
        s.points.push_back(p);
        s.depth.push_back(float(k));
    }
    Stroke r = simplify_stroke(s, 0.1f);
    EXPECT_EQ(r.points, (std::vector<glm::vec2>{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}));
    EXPECT_EQ(r.depth, (std::vector<float>{0, 10, 20, 30, 0}));
    Stroke tiny = simplify_stroke(s, 100.0f);
    EXPECT_EQ(tiny.points.size(), 4u);  // never collapses below a triangle
    EXPECT_EQ(tiny.points.front(), tiny.points.back());
}

TEST(Simplify, RingCollinearRemoval) {
    Ring r = {{0, 0}, {5, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 5}};
    EXPECT_EQ(remove_collinear(r), (Ring{{0, 0}, {10, 0}, {10, 10}, {0, 10}}));
}


// A straight stroke whose weight rises from 0 to 1 over its first half and stays: the points
// where the weight bends are kept (the width follows them), within kWeightTolerance of the chord
// everywhere; without weights it would be its two ends.
TEST(Simplify, StrokeKeepsItsWidthProfile) {
    Stroke s;
    for (int i = 0; i <= 40; ++i) {
        s.points.push_back(glm::vec2(float(i), 0.0f));
        s.depth.push_back(1.0f);
        s.weight.push_back(std::min(1.0f, float(i) / 20.0f));
    }
    const Stroke out = simplify_stroke(s, 0.4f);
    ASSERT_EQ(out.weight.size(), out.points.size());
    ASSERT_GE(out.points.size(), 3u);
    EXPECT_NE(std::find(out.points.begin(), out.points.end(), glm::vec2(20.0f, 0.0f)), out.points.end());
    for (int i = 0; i <= 40; ++i) {  // the drawn weight, linear between kept points
        std::size_t k = 0;
        while (k + 2 < out.points.size() && out.points[k + 1].x <= float(i)) ++k;
        const float f = (float(i) - out.points[k].x) / (out.points[k + 1].x - out.points[k].x);
        EXPECT_NEAR(out.weight[k] + f * (out.weight[k + 1] - out.weight[k]), s.weight[std::size_t(i)], kWeightTolerance + 1e-6f) << i;
    }
    Stroke plain = s;
    plain.weight.clear();
    EXPECT_EQ(simplify_stroke(plain, 0.4f).points.size(), 2u);
}

}  // namespace
}  // namespace penink
