#include "lines/trace_mask_outline.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace penink {
namespace {

PixelMask blank(int w, int h) { return {w, h, std::vector<std::uint8_t>(std::size_t(w) * h, 0)}; }
void fill_rect(PixelMask& m, int x0, int y0, int x1, int y1, std::uint8_t v) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) m.on[std::size_t(y) * m.width + x] = v;
}

TEST(TraceMaskOutline, SinglePixelIsAUnitSquareClockwiseOnScreen) {
    PixelMask m = blank(4, 4);
    fill_rect(m, 1, 2, 2, 3, 1);
    auto rings = trace_mask_outline(m, 0.0f);
    ASSERT_EQ(rings.size(), 1u);
    Ring expected = {{1, 2}, {2, 2}, {2, 3}, {1, 3}};
    EXPECT_EQ(rings[0], expected);
    EXPECT_DOUBLE_EQ(signed_area(rings[0]), 1.0);
}

TEST(TraceMaskOutline, SquareWithSquareHoleGivesTwoRingsWithExactAreas) {
    PixelMask m = blank(40, 40);
    fill_rect(m, 5, 5, 35, 35, 1);
    fill_rect(m, 12, 15, 22, 30, 0);
    auto rings = trace_mask_outline(m, 0.7f);
    ASSERT_EQ(rings.size(), 2u);
    EXPECT_DOUBLE_EQ(signed_area(rings[0]), 900.0);
    EXPECT_DOUBLE_EQ(signed_area(rings[1]), -150.0);
    EXPECT_EQ(rings[0].size(), 4u);
    EXPECT_EQ(rings[1].size(), 4u);
    EXPECT_EQ(rings[0][0], glm::vec2(5, 5));
    EXPECT_EQ(rings[1][0], glm::vec2(12, 15));
}

TEST(TraceMaskOutline, FilledDiscAreaWithinToleranceOfExact) {
    const int n = 200;
    const float r = 80.0f;
    PixelMask m = blank(n, n);
    int count = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            if (std::hypot(x + 0.5f - 100.0f, y + 0.5f - 100.0f) <= r) m.on[y * n + x] = 1, ++count;
    auto exact = trace_mask_outline(m, 0.0f);
    ASSERT_EQ(exact.size(), 1u);
    EXPECT_DOUBLE_EQ(signed_area(exact[0]), count);  // pixel-edge ring: exactly the pixel count
    auto rings = trace_mask_outline(m, 0.7f);
    ASSERT_EQ(rings.size(), 1u);
    const double disc = M_PI * r * r;
    EXPECT_NEAR(signed_area(rings[0]), disc, 0.01 * disc);
    EXPECT_LT(rings[0].size(), exact[0].size() / 2);
    for (glm::vec2 p : rings[0]) EXPECT_NEAR(std::hypot(p.x - 100.0f, p.y - 100.0f), r, 1.5f);
}

TEST(TraceMaskOutline, DiagonalPixelsAreSeparateRings) {
    PixelMask m = blank(3, 3);
    fill_rect(m, 0, 0, 1, 1, 1);
    fill_rect(m, 1, 1, 2, 2, 1);
    auto rings = trace_mask_outline(m, 0.0f);
    ASSERT_EQ(rings.size(), 2u);
    EXPECT_DOUBLE_EQ(signed_area(rings[0]), 1.0);
    EXPECT_DOUBLE_EQ(signed_area(rings[1]), 1.0);
}

TEST(TraceMaskOutline, OutlineStrokesAreClosedOuterRingsWithDepth) {
    PixelMask m = blank(20, 20);
    fill_rect(m, 2, 2, 18, 18, 1);
    fill_rect(m, 8, 8, 12, 12, 0);
    DepthImage d{20, 20, std::vector<float>(400, INFINITY)};
    for (int y = 2; y < 18; ++y)
        for (int x = 2; x < 18; ++x) d.depth[y * 20 + x] = 5.0f;
    auto rings = trace_mask_outline(m, 0.5f);
    auto outer = outline_strokes(rings, d);
    ASSERT_EQ(outer.size(), 1u);
    EXPECT_EQ(outer[0].points.size(), 5u);
    EXPECT_EQ(outer[0].points.front(), outer[0].points.back());
    EXPECT_EQ(outer[0].kind, "outline");
    for (float z : outer[0].depth) EXPECT_FLOAT_EQ(z, 5.0f);
    EXPECT_EQ(outline_strokes(rings, d, true).size(), 2u);
}

TEST(TraceMaskOutline, MalformedMaskIsAnError) {
    PixelMask m{3, 3, std::vector<std::uint8_t>(8, 0)};
    try {
        trace_mask_outline(m);
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: lines: coverage mask: size 3x3 does not match 8 values");
    }
}

}  // namespace
}  // namespace penink
