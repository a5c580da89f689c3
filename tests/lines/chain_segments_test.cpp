#include "lines/chain_segments.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace penink {
namespace {

std::vector<glm::vec2> zigzag(int n) {
    std::vector<glm::vec2> p;
    for (int i = 0; i < n; ++i) p.emplace_back(10.0f * i, (i % 2) ? 10.0f : 0.0f);
    return p;
}

TEST(ChainSegments, ShuffledReversedZigZagBecomesOnePolylineInOrder) {
    const auto pts = zigzag(12);
    std::vector<ImageSegment> segs;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i)  // every other segment reversed
        segs.push_back(i % 2 ? ImageSegment{pts[i + 1], pts[i], float(i + 1), float(i), 1.0f}
                             : ImageSegment{pts[i], pts[i + 1], float(i), float(i + 1), 3.0f});
    const std::vector<int> order = {7, 2, 9, 0, 5, 10, 3, 8, 1, 6, 4};  // fixed shuffle
    std::vector<ImageSegment> shuffled;
    for (int k : order) shuffled.push_back(segs[k]);
    auto out = chain_segments(shuffled);
    ASSERT_EQ(out.size(), 1u);
    auto got = out[0].points;
    auto depth = out[0].depth;
    if (got.front() != pts.front()) std::reverse(got.begin(), got.end()), std::reverse(depth.begin(), depth.end());
    EXPECT_EQ(got, pts);
    for (std::size_t i = 0; i < depth.size(); ++i) EXPECT_FLOAT_EQ(depth[i], float(i));
    EXPECT_FLOAT_EQ(out[0].strength, 23.0f / 11.0f);  // mean of six 3s and five 1s
}

TEST(ChainSegments, TJunctionIsKeptAsThreeChains) {
    std::vector<ImageSegment> segs = {
        {{0, 0}, {10, 0}}, {{10, 0}, {20, 0}}, {{20, 0}, {30, 0}},
        {{40, 0}, {30, 0}}, {{20, 0}, {20, 10}}, {{20, 10}, {20, 20}}};
    auto out = chain_segments(segs);
    ASSERT_EQ(out.size(), 3u);
    std::vector<std::size_t> sizes;
    for (const Stroke& s : out) {
        EXPECT_TRUE(s.points.front() == glm::vec2(20, 0) || s.points.back() == glm::vec2(20, 0));
        sizes.push_back(s.points.size());
    }
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes, (std::vector<std::size_t>{3, 3, 3}));
}

TEST(ChainSegments, ToleranceIsRespected) {
    std::vector<ImageSegment> segs = {{{0, 0}, {10, 0}}, {{10.4f, 0}, {20, 0}}, {{20.8f, 0}, {30, 0}}};
    ChainParams p;
    p.tolerance = 0.5f;
    auto out = chain_segments(segs, p);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].points.size(), 3u);
    EXPECT_NEAR(out[0].points[1].x, 10.2f, 1e-5f);  // joint = mean of the merged ends
    p.tolerance = 1.0f;
    EXPECT_EQ(chain_segments(segs, p).size(), 1u);
    p.tolerance = 0.3f;
    EXPECT_EQ(chain_segments(segs, p).size(), 3u);
}

TEST(ChainSegments, SquareIsOneClosedChainAndStrengthRules) {
    std::vector<ImageSegment> segs = {{{0, 0}, {10, 0}, 0, 0, 1.0f}, {{10, 0}, {10, 10}, 0, 0, 2.0f},
                                      {{0, 10}, {10, 10}, 0, 0, 3.0f}, {{0, 10}, {0, 0}, 0, 0, 6.0f}};
    ChainParams p;
    auto out = chain_segments(segs, p);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].points.size(), 5u);
    EXPECT_EQ(out[0].points.front(), out[0].points.back());
    EXPECT_FLOAT_EQ(out[0].strength, 3.0f);
    p.strength = StrengthRule::max;
    EXPECT_FLOAT_EQ(chain_segments(segs, p)[0].strength, 6.0f);
    p.max_turn_deg = 45.0f;  // every corner turns 90 degrees: four separate strokes
    EXPECT_EQ(chain_segments(segs, p).size(), 4u);
}

TEST(ChainSegments, DuplicateAndCollapsedSegmentsAreDropped) {
    std::vector<ImageSegment> segs = {{{0, 0}, {10, 0}}, {{10, 0}, {0, 0}}, {{5, 5}, {5.1f, 5}}, {{10, 0}, {20, 0}}};
    auto out = chain_segments(segs);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].points, (std::vector<glm::vec2>{{0, 0}, {10, 0}, {20, 0}}));
}

TEST(JoinStrokes, JoinsEndsWithinToleranceKeepsJunctionsAndKinds) {
    std::vector<Stroke> in = {
        {{{0, 0}, {5, 1}, {10, 0}}, {1, 1, 1}, 1.0f, "crease"},
        {{{20, 0}, {15, 1}, {10.2f, 0}}, {2, 2, 2}, 3.0f, "crease"},
        {{{20, 0}, {25, 0}}, {2, 2}, 1.0f, "ridge"},
        {{{50, 50}, {60, 50}, {60, 60}, {50, 50}}, {0, 0, 0, 0}, 1.0f, "crease", {}}};
    auto out = join_strokes(in, 0.5f);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0].kind, "crease");
    EXPECT_EQ(out[0].points.size(), 4u);  // closed stroke passes through first
    EXPECT_EQ(out[1].points.size(), 5u);
    EXPECT_FLOAT_EQ(out[1].strength, 2.0f);
    EXPECT_EQ(out[2].kind, "ridge");
    EXPECT_EQ(join_strokes(in, 0.1f).size(), 4u);
}

}  // namespace
}  // namespace penink
