// line_metrics: loops counted by size, doubled length only where strokes run side by side (not
// where they cross or meet at a junction).
#include <gtest/gtest.h>

#include "lines/line_metrics.hpp"

using namespace penink;

namespace {
Stroke line(std::vector<glm::vec2> p) {
    Stroke s;
    s.depth.assign(p.size(), 1.0f);
    s.points = std::move(p);
    return s;
}
}  // namespace

TEST(LineMetrics, ParallelStrokesAreDoubledCrossingsAreNot) {
    // two 20 px strokes 1 px apart: all of both is doubled
    LineMetrics m = line_metrics({line({{0, 0}, {20, 0}}), line({{0, 1}, {20, 1}})});
    EXPECT_EQ(m.paths, 2u);
    EXPECT_NEAR(m.length, 40.0, 1e-6);
    EXPECT_NEAR(m.doubled_share(), 1.0, 0.02);
    // 3 px apart: none
    EXPECT_EQ(line_metrics({line({{0, 0}, {20, 0}}), line({{0, 3}, {20, 3}})}).doubled_length, 0.0);
    // a crossing and a T-junction touch each other over less than 4 px
    EXPECT_EQ(line_metrics({line({{0, 10}, {20, 10}}), line({{10, 0}, {10, 20}})}).doubled_length, 0.0);
    EXPECT_EQ(line_metrics({line({{0, 10}, {20, 10}}), line({{10, 10}, {10, 30}})}).doubled_length, 0.0);
    // a 10 px stroke 1 px beside a 40 px one: all of it, and of the long one the 10 px plus
    // sqrt(1.5^2 - 1) = 1.12 px beyond each end (the quarter-pixel samples round it)
    m = line_metrics({line({{0, 0}, {40, 0}}), line({{15, 1}, {25, 1}})});
    EXPECT_NEAR(m.doubled_length, 10.0 + 10.0 + 2.0 * 1.118, 0.3);
}

TEST(LineMetrics, SmallClosedLoopsCounted) {
    const Stroke small = line({{0, 0}, {10, 0}, {10, 5}, {0, 5}, {0, 0}});
    const Stroke big = line({{0, 0}, {30, 0}, {30, 5}, {0, 5}, {0, 0}});
    const Stroke open = line({{0, 0}, {10, 0}, {10, 5}});
    const LineMetrics m = line_metrics({small, big, open});
    EXPECT_EQ(m.paths, 3u);
    EXPECT_EQ(m.small_loops, 1u);
    EXPECT_FLOAT_EQ(stroke_extent(big), 30.0f);
    EXPECT_DOUBLE_EQ(stroke_length(open), 15.0);
}
