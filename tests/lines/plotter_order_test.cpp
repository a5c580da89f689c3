#include "lines/plotter_order.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace penink {
namespace {

Stroke line(glm::vec2 a, glm::vec2 b) { return {{a, b}, {1.0f, 2.0f}, 1.0f, "x", {}}; }

TEST(PlotterOrder, HandCaseReordersAndReverses) {
    // Input order: far stroke first, then a reversed near one.
    std::vector<Stroke> s = {line({100, 0}, {110, 0}), line({10, 0}, {0, 0}), line({20, 0}, {30, 0})};
    EXPECT_DOUBLE_EQ(pen_up_travel(s), 100.0 + 100.0 + 20.0);
    PlotterStats st = order_for_plotter(s);
    EXPECT_EQ(st.count, 3u);
    EXPECT_DOUBLE_EQ(st.length, 30.0);
    EXPECT_DOUBLE_EQ(st.travel_before, 220.0);
    EXPECT_DOUBLE_EQ(st.travel_after, 0.0 + 10.0 + 70.0);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s[0].points, (std::vector<glm::vec2>{{0, 0}, {10, 0}}));
    EXPECT_EQ(s[0].depth, (std::vector<float>{2.0f, 1.0f}));  // reversed with its points
    EXPECT_EQ(s[1].points.front(), glm::vec2(20, 0));
    EXPECT_EQ(s[2].points.front(), glm::vec2(100, 0));
}

TEST(PlotterOrder, HomeAndDiagonalHandCase) {
    std::vector<Stroke> s = {line({3, 4}, {3, 10}), line({6, 8}, {0, 0}), line({0, 20}, {3, 16})};
    PlotterStats st = order_for_plotter(s, {0, 0});
    // Before: home -> (3,4): 5; (3,10) -> (6,8): sqrt(13); (0,0) -> (0,20): 20.
    EXPECT_NEAR(st.travel_before, 5.0 + std::sqrt(13.0) + 20.0, 1e-5);
    // After: B reversed from home (0); from (6,8) A's end (3,10) is nearer (sqrt 13) than its
    // start (5): A reversed; from (3,4) C's end (3,16) at 12: C reversed.
    EXPECT_NEAR(st.travel_after, std::sqrt(13.0) + 12.0, 1e-5);
    EXPECT_EQ(s[0].points, (std::vector<glm::vec2>{{0, 0}, {6, 8}}));
    EXPECT_EQ(s[1].points, (std::vector<glm::vec2>{{3, 10}, {3, 4}}));
    EXPECT_EQ(s[2].points, (std::vector<glm::vec2>{{3, 16}, {0, 20}}));
}

TEST(PlotterOrder, ManyStrokesKeepAllAndReduceTravel) {
    std::vector<Stroke> s;
    std::uint64_t x = 12345;
    auto next = [&x]() { x = x * 6364136223846793005ull + 1442695040888963407ull; return float((x >> 40) % 1000); };
    for (int i = 0; i < 20000; ++i) {
        glm::vec2 a(next(), next());
        s.push_back(line(a, a + glm::vec2(3.0f, 1.0f)));
    }
    PlotterStats st = order_for_plotter(s);
    EXPECT_EQ(s.size(), 20000u);
    EXPECT_NEAR(st.length, 20000 * std::sqrt(10.0), 1e-3 * st.length);
    EXPECT_LT(st.travel_after, 0.1 * st.travel_before);
    EXPECT_DOUBLE_EQ(st.travel_after, pen_up_travel(s));
}

}  // namespace
}  // namespace penink
