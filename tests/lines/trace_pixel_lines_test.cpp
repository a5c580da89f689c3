#include "lines/trace_pixel_lines.hpp"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "lines/thin_mask.hpp"

namespace penink {
namespace {

PixelMask blank(int w, int h) { return {w, h, std::vector<std::uint8_t>(std::size_t(w) * h, 0)}; }
void set(PixelMask& m, int x, int y) { m.on[std::size_t(y) * m.width + x] = 1; }
DepthImage flat_depth(int w, int h, float z) { return {w, h, std::vector<float>(std::size_t(w) * h, z)}; }

bool adjacent8(glm::vec2 a, glm::vec2 b) {
    return std::fabs(a.x - b.x) <= 1.0f && std::fabs(a.y - b.y) <= 1.0f && a != b;
}

TEST(TracePixelLines, HorizontalLineIsOneChainThroughPixelCentres) {
    PixelMask m = blank(20, 10);
    for (int x = 3; x <= 15; ++x) set(m, x, 4);
    auto s = trace_pixel_lines(m, flat_depth(20, 10, 7.5f));
    ASSERT_EQ(s.size(), 1u);
    ASSERT_EQ(s[0].points.size(), 13u);
    EXPECT_EQ(s[0].points.front(), glm::vec2(3.5f, 4.5f));
    EXPECT_EQ(s[0].points.back(), glm::vec2(15.5f, 4.5f));
    for (float z : s[0].depth) EXPECT_FLOAT_EQ(z, 7.5f);
    EXPECT_EQ(s[0].kind, "silhouette");
}

TEST(TracePixelLines, LShapeIsOneChainKeepingBothEnds) {
    PixelMask m = blank(20, 20);
    for (int y = 2; y <= 12; ++y) set(m, 2, y);
    for (int x = 2; x <= 12; ++x) set(m, x, 12);
    auto s = trace_pixel_lines(m, {});
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].points.front(), glm::vec2(2.5f, 2.5f));  // scan order: top end first
    EXPECT_EQ(s[0].points.back(), glm::vec2(12.5f, 12.5f));
    EXPECT_EQ(s[0].points.size(), 20u);  // 21 pixels, corner pixel cut by 8-thinning
    for (std::size_t i = 1; i < s[0].points.size(); ++i)
        EXPECT_TRUE(adjacent8(s[0].points[i - 1], s[0].points[i]));
    for (float z : s[0].depth) EXPECT_EQ(z, 0.0f);  // no depth image: 0
}

TEST(TracePixelLines, TJunctionGivesThreeChainsMeetingAtTheJunction) {
    PixelMask m = blank(30, 30);
    for (int x = 2; x <= 26; ++x) set(m, x, 5);
    for (int y = 5; y <= 25; ++y) set(m, 14, y);
    auto s = trace_pixel_lines(m, {});
    ASSERT_EQ(s.size(), 3u);
    glm::vec2 j = s[0].points.back();
    for (const Stroke& c : s) {
        bool touches = c.points.front() == j || c.points.back() == j;
        EXPECT_TRUE(touches);
    }
    EXPECT_NEAR(j.x, 14.5f, 1.0f);
    EXPECT_NEAR(j.y, 5.5f, 1.0f);
    std::vector<glm::vec2> ends;
    for (const Stroke& c : s)
        for (glm::vec2 p : {c.points.front(), c.points.back()})
            if (p != j) ends.push_back(p);
    ASSERT_EQ(ends.size(), 3u);
    EXPECT_EQ(ends[0], glm::vec2(2.5f, 5.5f));
    EXPECT_EQ(ends[1], glm::vec2(26.5f, 5.5f));
    EXPECT_EQ(ends[2], glm::vec2(14.5f, 25.5f));
}

TEST(TracePixelLines, CircleIsOneClosedChain) {
    PixelMask m = blank(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            float r = std::hypot(x + 0.5f - 32.0f, y + 0.5f - 32.0f);
            if (std::fabs(r - 20.0f) <= 0.75f) set(m, x, y);
        }
    auto s = trace_pixel_lines(m, flat_depth(64, 64, 3.0f));
    ASSERT_EQ(s.size(), 1u);
    const auto& p = s[0].points;
    EXPECT_EQ(p.front(), p.back());
    EXPECT_GT(p.size(), 100u);
    for (std::size_t i = 1; i < p.size(); ++i) {
        EXPECT_TRUE(adjacent8(p[i - 1], p[i]));
        EXPECT_NEAR(std::hypot(p[i].x - 32.0f, p[i].y - 32.0f), 20.0f, 1.0f);
    }
}

TEST(TracePixelLines, TwoPixelThickDiagonalIsOneChainWithoutSpurs) {
    PixelMask m = blank(50, 50);
    for (int i = 5; i <= 40; ++i) {
        set(m, i, i);
        set(m, i + 1, i);
    }
    auto s = trace_pixel_lines(m, {});
    ASSERT_EQ(s.size(), 1u);
    const auto& p = s[0].points;
    glm::vec2 a = p.front(), b = p.back();
    if (a.y > b.y) std::swap(a, b);
    EXPECT_NEAR(a.y, 5.5f, 1.0f);
    EXPECT_NEAR(b.y, 40.5f, 1.0f);
    for (std::size_t i = 1; i < p.size(); ++i) EXPECT_TRUE(adjacent8(p[i - 1], p[i]));
    EXPECT_LE(p.size(), 38u);  // about one point per row: no staircase, no spur
}

TEST(TracePixelLines, MinPixelsDropsShortChains) {
    PixelMask m = blank(20, 20);
    for (int x = 2; x <= 4; ++x) set(m, x, 2);   // 3 pixels
    for (int x = 2; x <= 11; ++x) set(m, x, 8);  // 10 pixels
    set(m, 15, 15);                              // isolated pixel
    TraceParams p;
    p.min_pixels = 4;
    auto s = trace_pixel_lines(m, {}, p);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].points.size(), 10u);
    p.min_pixels = 3;
    EXPECT_EQ(trace_pixel_lines(m, {}, p).size(), 2u);
    p.min_pixels = 11;
    EXPECT_EQ(trace_pixel_lines(m, {}, p).size(), 0u);
}

TEST(TracePixelLines, DepthOfEmptyPixelComesFromNearestValidNeighbour) {
    PixelMask m = blank(10, 10);
    for (int x = 2; x <= 7; ++x) set(m, x, 5);
    DepthImage d = flat_depth(10, 10, std::numeric_limits<float>::infinity());
    for (int x = 0; x < 10; ++x) d.depth[6 * 10 + x] = 4.0f;  // row below the line
    d.depth[4 * 10 + 3] = 2.0f;                               // corner-free edge neighbour above x=3
    auto s = trace_pixel_lines(m, d);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_FLOAT_EQ(s[0].depth[0], 4.0f);
    EXPECT_FLOAT_EQ(s[0].depth[1], 2.0f);  // x=3: nearer surface wins among edge neighbours
    EXPECT_FLOAT_EQ(s[0].depth[5], 4.0f);
}

TEST(TracePixelLines, MismatchedDepthImageIsAnError) {
    PixelMask m = blank(10, 10);
    try {
        trace_pixel_lines(m, flat_depth(5, 5, 1.0f));
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: lines: depth image 5x5 does not match line mask 10x10");
    }
    m.on.pop_back();
    try {
        trace_pixel_lines(m, {});
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: lines: line mask: size 10x10 does not match 99 values");
    }
}

// A large crossing grid: every pixel chain is found (its speed is measured in bench/lines_bench.cpp).
TEST(TracePixelLines, LargeCrossingGrid) {
    const int n = 2000;
    PixelMask m = blank(n, n);
    std::size_t count = 0;
    for (int y = 10; y < n - 10; y += 20)  // 100 horizontal lines, 2 px thick
        for (int x = 10; x < n - 10; ++x) set(m, x, y), set(m, x, y + 1), count += 2;
    for (int x = 15; x < n - 10; x += 200)  // vertical lines crossing them
        for (int y = 10; y < n - 10; ++y) set(m, x, y), ++count;
    ASSERT_GT(count, 400000u);
    const auto s = trace_pixel_lines(m, {});
    // 99 horizontal lines cut by 10 vertical ones give at most 99 * 11 + 10 * 100 chains; the
    // junction rules merge a few, so the count is close to that bound and far above the line count.
    EXPECT_GT(s.size(), 1000u);
    EXPECT_LE(s.size(), 99u * 11u + 10u * 100u);
    float length = 0.0f;
    for (const auto& st : s)
        for (std::size_t i = 1; i < st.points.size(); ++i) length += glm::length(st.points[i] - st.points[i - 1]);
    // Skeleton length: 99 lines of 1980 px and 10 of 1980 px, minus what junctions take.
    EXPECT_GT(length, 0.97f * 109.0f * 1980.0f);
    EXPECT_LT(length, 1.01f * 109.0f * 1980.0f);
}

TEST(ThinMask, ConnectivityNumber) {
    EXPECT_EQ(connectivity_number(0b00000100), 1);  // E only: end point
    EXPECT_EQ(connectivity_number(0b01000100), 2);  // W, E: line interior
    EXPECT_EQ(connectivity_number(0b00000101), 1);  // N, E: staircase corner
    EXPECT_EQ(connectivity_number(0b01010101), 0);  // N, E, S, W: no background around
}

}  // namespace
}  // namespace penink
