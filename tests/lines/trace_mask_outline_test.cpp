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

// Signed shoelace area (pixels^2) of a ring: the header's orientation contract says > 0 for outer
// boundaries, < 0 for holes.
double signed_area(const Ring& ring) {
    double a = 0.0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
        const glm::vec2 p = ring[i], q = ring[(i + 1) % n];
        a += double(p.x) * q.y - double(q.x) * p.y;
    }
    return 0.5 * a;
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
