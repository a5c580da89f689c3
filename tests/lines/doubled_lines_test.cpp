// merge_doubled: of two strokes running a pixel apart the stronger stays whole and the other is cut
// where they run together; crossings and T-junctions are left alone; a crease yields to a
// silhouette given as `above`.
#include <gtest/gtest.h>

#include "lines/doubled_lines.hpp"
#include "lines/line_metrics.hpp"

using namespace penink;

namespace {
Stroke line(std::vector<glm::vec2> p, float strength = 1.0f) {
    Stroke s;
    s.depth.assign(p.size(), 1.0f);
    s.points = std::move(p);
    s.strength = strength;
    return s;
}
}  // namespace

TEST(DoubledLines, ParallelStrokesAPixelApartBecomeOne) {
    // a weaker 60 px stroke 1 px beside a stronger 100 px one for its middle 40 px
    const Stroke strong = line({{0, 0}, {100, 0}}, 2.0f);
    const Stroke weak = line({{20, 5}, {30, 1}, {70, 1}, {80, 5}}, 1.0f);
    const std::vector<Stroke> out = merge_doubled({weak, strong}, 1.5f, 4.0f);
    ASSERT_EQ(out.size(), 3u);  // the weak one's two ends, then the strong one
    EXPECT_EQ(out[2].points, strong.points);
    EXPECT_LT(line_metrics(out).doubled_share(), 0.02);
    // what is left of the weak stroke: its slanted ends, each ending about 1.5 px from the strong one
    for (const Stroke& piece : {out[0], out[1]}) {
        EXPECT_GT(stroke_length(piece), 3.0);
        EXPECT_LT(stroke_length(piece), 12.0);
    }
    // equal strength: the longer stays whole
    const std::vector<Stroke> tie = merge_doubled({line({{0, 1}, {50, 1}}), line({{0, 0}, {100, 0}})}, 1.5f, 4.0f);
    ASSERT_EQ(tie.size(), 1u);
    EXPECT_EQ(tie[0].points.back(), glm::vec2(100, 0));
}

TEST(DoubledLines, CrossingsAndJunctionsStay) {
    const std::vector<Stroke> cross = {line({{0, 10}, {20, 10}}), line({{10, 0}, {10, 20}})};
    EXPECT_EQ(merge_doubled(cross, 1.5f, 4.0f).size(), 2u);
    const std::vector<Stroke> t = {line({{0, 10}, {20, 10}}, 2.0f), line({{10, 10}, {10, 30}})};
    const std::vector<Stroke> out = merge_doubled(t, 1.5f, 4.0f);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[1].points.front(), glm::vec2(10, 10));  // the stem still ends on the bar
}

TEST(DoubledLines, CreaseYieldsToSilhouette) {
    const std::vector<Stroke> sil = {line({{0, 0}, {100, 0}}, 0.1f)};  // weaker, but above
    const std::vector<Stroke> crease = {line({{10, 1}, {90, 1}}, 5.0f)};
    EXPECT_TRUE(merge_doubled(crease, 1.5f, 4.0f, sil).empty());
    EXPECT_EQ(merge_doubled(crease, 0.0f, 4.0f, sil).size(), 1u);  // width 0: no merging
}
