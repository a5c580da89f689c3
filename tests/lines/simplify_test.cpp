#include "lines/simplify.hpp"

#include <gtest/gtest.h>

namespace penink {
namespace {

TEST(Simplify, DouglasPeuckerKnownAnswer) {
    // Classic example: deviations 0.1 (i=1), 3 (i=3), 0.2 (i=2, 4) from the chords.
    std::vector<glm::vec2> p = {{0, 0}, {1, 0.1f}, {2, -0.1f}, {3, 5}, {4, 6}, {5, 7}, {6, 8.1f}, {7, 9}};
    EXPECT_EQ(douglas_peucker_indices(p, 0.5f), (std::vector<std::size_t>{0, 2, 3, 7}));
    EXPECT_EQ(douglas_peucker_indices(p, 10.0f), (std::vector<std::size_t>{0, 7}));
    std::vector<glm::vec2> line = {{0, 0}, {1, 1}, {2, 2}, {3, 0}};
    EXPECT_EQ(douglas_peucker_indices(line, 0.0f), (std::vector<std::size_t>{0, 2, 3}));
}

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
    EXPECT_FLOAT_EQ(point_segment_distance({5, 3}, {0, 0}, {10, 0}), 3.0f);
    EXPECT_FLOAT_EQ(point_segment_distance({13, 4}, {0, 0}, {10, 0}), 5.0f);
}

}  // namespace
}  // namespace penink
