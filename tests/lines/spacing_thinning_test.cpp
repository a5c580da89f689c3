// thin_by_spacing: the weaker of two close parallel strokes goes, distant ones stay, a crossing
// stroke is cut with a gap of twice the spacing around the stronger one, short pieces drop, equal
// strengths keep input order, depth is interpolated on inserted points.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lines/spacing_thinning.hpp"

using namespace penink;

namespace {

Stroke line(glm::vec2 a, glm::vec2 b, float strength, float depth_a = 100.0f, float depth_b = 100.0f) {
    Stroke s;
    s.points = {a, b};
    s.depth = {depth_a, depth_b};
    s.strength = strength;
    s.kind = "crease";
    return s;
}

float length(const Stroke& s) {
    float l = 0.0f;
    for (std::size_t i = 1; i < s.points.size(); ++i) l += glm::length(s.points[i] - s.points[i - 1]);
    return l;
}

}  // namespace

TEST(SpacingThinning, CloseParallelWeakerStrokeRemoved) {
    const std::vector<Stroke> in = {line({0, 50}, {100, 50}, 0.2f), line({0, 52}, {100, 52}, 0.5f)};
    const auto out = thin_by_spacing(in, 4.0f);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_FLOAT_EQ(out[0].strength, 0.5f);
    EXPECT_EQ(out[0].kind, "crease");
    EXPECT_FLOAT_EQ(out[0].points.front().y, 52.0f);
    EXPECT_FLOAT_EQ(out[0].points.front().x, 0.0f);
    EXPECT_FLOAT_EQ(out[0].points.back().x, 100.0f);
    EXPECT_NEAR(length(out[0]), 100.0f, 1e-3);
    // Densified to at most half a spacing between points: 100 px / 2 px.
    EXPECT_EQ(out[0].points.size(), 51u);
    for (std::size_t i = 1; i < out[0].points.size(); ++i)
        EXPECT_LE(glm::length(out[0].points[i] - out[0].points[i - 1]), 2.0f + 1e-4f);
}

TEST(SpacingThinning, DistantParallelStrokesBothKept) {
    const std::vector<Stroke> in = {line({0, 50}, {100, 50}, 0.2f), line({0, 60}, {100, 60}, 0.5f)};
    const auto out = thin_by_spacing(in, 4.0f);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_FLOAT_EQ(out[0].strength, 0.5f);  // strongest first
    EXPECT_FLOAT_EQ(out[1].strength, 0.2f);
    EXPECT_NEAR(length(out[0]), 100.0f, 1e-3);
    EXPECT_NEAR(length(out[1]), 100.0f, 1e-3);
    EXPECT_EQ(thin_by_spacing(in, 0.0f).size(), 2u);  // spacing 0: input as is
    EXPECT_EQ(thin_by_spacing(in, 0.0f)[0].points.size(), 2u);
}

TEST(SpacingThinning, CrossingStrokeCutWithGap) {
    const std::vector<Stroke> in = {line({50, 0}, {50, 100}, 0.1f, 10.0f, 30.0f), line({0, 50}, {100, 50}, 0.9f)};
    const auto out = thin_by_spacing(in, 4.0f);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_FLOAT_EQ(out[0].strength, 0.9f);
    EXPECT_NEAR(length(out[0]), 100.0f, 1e-3);  // the strong one is whole
    // The weak one keeps points at distance >= 4 from the strong one's points (every 2 px):
    // y in [0, 46] and [54, 100].
    const Stroke &lo = out[1], &hi = out[2];
    EXPECT_FLOAT_EQ(lo.strength, 0.1f);
    EXPECT_NEAR(lo.points.front().y, 0.0f, 1e-4);
    EXPECT_NEAR(lo.points.back().y, 46.0f, 1e-4);
    EXPECT_NEAR(hi.points.front().y, 54.0f, 1e-4);
    EXPECT_NEAR(hi.points.back().y, 100.0f, 1e-4);
    for (const Stroke* s : {&lo, &hi})
        for (const glm::vec2& p : s->points) EXPECT_FLOAT_EQ(p.x, 50.0f);
    // Depth interpolated linearly along the original segment (10 at y = 0, 30 at y = 100).
    ASSERT_EQ(lo.depth.size(), lo.points.size());
    EXPECT_NEAR(lo.depth.back(), 10.0f + 20.0f * 0.46f, 1e-4);
    EXPECT_NEAR(hi.depth.front(), 10.0f + 20.0f * 0.54f, 1e-4);
    EXPECT_NEAR(hi.depth.back(), 30.0f, 1e-4);
}

TEST(SpacingThinning, ShortPiecesDropped) {
    // Default min_length = 3 spacings = 12 px: a 10 px stroke goes, a 14 px one stays.
    const std::vector<Stroke> in = {line({0, 0}, {10, 0}, 0.5f), line({0, 40}, {14, 40}, 0.5f)};
    const auto out = thin_by_spacing(in, 4.0f);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_FLOAT_EQ(out[0].points.front().y, 40.0f);
    EXPECT_EQ(thin_by_spacing(in, 4.0f, 5.0f).size(), 2u);
    EXPECT_EQ(thin_by_spacing(in, 4.0f, 20.0f).size(), 0u);
    // A crossing stroke whose piece below the strong line is 6 px long loses that piece.
    const std::vector<Stroke> cross = {line({50, 40}, {50, 100}, 0.1f), line({0, 50}, {100, 50}, 0.9f)};
    const auto cut = thin_by_spacing(cross, 4.0f);
    ASSERT_EQ(cut.size(), 2u);
    EXPECT_NEAR(cut[1].points.front().y, 54.0f, 1e-4);
    EXPECT_NEAR(cut[1].points.back().y, 100.0f, 1e-4);
}

TEST(SpacingThinning, StrokesTooShortToLeaveAPieceBlockNothing) {
    // A strong 10 px stroke leaves nothing (min 12 px), so the weaker line 2 px beside it stays
    // whole; a 12 px one (exactly the minimum, in 3 segments) stays and cuts the weaker line.
    const Stroke weak = line({0, 52}, {100, 52}, 0.2f);
    const auto out = thin_by_spacing({line({40, 50}, {50, 50}, 0.9f), weak}, 4.0f);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_FLOAT_EQ(out[0].strength, 0.2f);
    EXPECT_FLOAT_EQ(length(out[0]), 100.0f);
    Stroke twelve = line({40, 50}, {52, 50}, 0.9f);
    twelve.points = {{40, 50}, {44, 50}, {48, 50}, {52, 50}}, twelve.depth.assign(4, 100.0f);
    const auto cut = thin_by_spacing({twelve, weak}, 4.0f);
    ASSERT_EQ(cut.size(), 3u);  // the 12 px stroke and the weaker line's two ends
    EXPECT_FLOAT_EQ(length(cut[0]), 12.0f);
    EXPECT_LT(length(cut[1]) + length(cut[2]), 90.0f);
}

TEST(SpacingThinning, EqualStrengthKeepsInputOrder) {
    const Stroke a = line({0, 50}, {100, 50}, 0.3f), b = line({0, 51}, {100, 51}, 0.3f);
    const auto ab = thin_by_spacing({a, b}, 4.0f), ba = thin_by_spacing({b, a}, 4.0f);
    ASSERT_EQ(ab.size(), 1u);
    ASSERT_EQ(ba.size(), 1u);
    EXPECT_FLOAT_EQ(ab[0].points.front().y, 50.0f);
    EXPECT_FLOAT_EQ(ba[0].points.front().y, 51.0f);
}

TEST(SpacingThinning, NegativeCoordinatesHashCorrectly) {
    // Cells at negative coordinates must not alias: strokes far apart in -x/-y all stay, and a
    // close pair straddling zero still conflicts.
    const std::vector<Stroke> in = {line({-300, -200}, {-200, -200}, 0.5f), line({-300, 200}, {-200, 200}, 0.4f),
                                    line({200, -200}, {300, -200}, 0.3f), line({-50, -1}, {50, -1}, 0.2f),
                                    line({-50, 1}, {50, 1}, 0.1f)};
    const auto out = thin_by_spacing(in, 4.0f);
    ASSERT_EQ(out.size(), 4u);
    EXPECT_FLOAT_EQ(out[3].points.front().y, -1.0f);
}
