// InkCoverage (lines/hachure_coverage.hpp): the gain of ink laid in image cells against the target
// tone sampled in them, on hand-made fields whose gains follow in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lines/hachure_coverage.hpp"

using namespace penink;

namespace {

// A 64 x 64 image of 8 px cells, all terrain, the target `tone` sampled four times per cell.
InkCoverage uniform_target(double tone) {
    InkCoverage c(64, 64, 8.0f);
    for (int y = 2; y < 64; y += 4)
        for (int x = 2; x < 64; x += 4) c.add_target(glm::vec2(x, y), tone);
    return c;
}

// Vertical lines every `spacing` px, `width` px wide, over the whole image.
void hatch(InkCoverage& c, float spacing, double width, bool fixed = false) {
    for (float x = 0.5f * spacing; x < 64.0f; x += spacing) c.add_ink(glm::vec2(x, 0.0f), glm::vec2(x, 64.0f), width, fixed);
}

}  // namespace

// Lines 1 px wide every 4 px lay 0.25 of the paper: against a target of 0.5 the gain is 2
// everywhere, against 0.125 it is 0.5; the ink share is the inverse.
TEST(InkCoverage, GainIsTargetOverInk) {
    for (double tone : {0.5, 0.125}) {
        InkCoverage c = uniform_target(tone);
        hatch(c, 4.0f, 1.0);
        c.update(4.0);
        EXPECT_NEAR(c.ink_share(), 0.25 / tone, 1e-9);
        for (glm::vec2 p : {glm::vec2(3, 3), glm::vec2(30, 41), glm::vec2(63, 63)})
            EXPECT_NEAR(c.gain(p, 4.0), tone / 0.25, 1e-9) << p.x << " " << p.y;
    }
}

// No ink around a target: the largest gain; no target at all: gain 1 (the pen is left as it is).
TEST(InkCoverage, NoInkOrNoTarget) {
    InkCoverage c = uniform_target(0.4);
    c.update(3.0);
    EXPECT_DOUBLE_EQ(c.gain(glm::vec2(20, 20), 3.0), 3.0);
    InkCoverage none(64, 64, 8.0f);
    hatch(none, 4.0f, 1.0);
    none.update(3.0);
    EXPECT_DOUBLE_EQ(none.gain(glm::vec2(20, 20), 3.0), 1.0);
}

// Fixed ink (the lines yielded to) counts and survives clear_ink; ink past a cell's terrain
// pixels does not count twice (overlapping strokes).
TEST(InkCoverage, FixedInkAndSaturation) {
    InkCoverage c = uniform_target(0.5);
    hatch(c, 8.0f, 2.0, true);  // 0.25 fixed
    hatch(c, 8.0f, 2.0);        // 0.25 more
    c.update(4.0);
    EXPECT_NEAR(c.gain(glm::vec2(32, 32), 4.0), 1.0, 1e-9);
    c.clear_ink();
    c.update(4.0);
    EXPECT_NEAR(c.gain(glm::vec2(32, 32), 4.0), 2.0, 1e-9);
    hatch(c, 2.0f, 4.0);  // twice the paper
    c.update(4.0);
    EXPECT_NEAR(c.ink_share(), 1.0 / 0.5, 1e-9);
}

// Terrain counted from a depth image: a cell half terrain asks for half the ink.
TEST(InkCoverage, TerrainFromTheDepthImage) {
    DepthImage d{64, 64, std::vector<float>(64 * 64, std::numeric_limits<float>::infinity())};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x) d.depth[std::size_t(y) * 64 + x] = 100.0f;
    InkCoverage c(64, 64, 64.0f);  // one cell
    c.set_terrain(d);
    c.add_target(glm::vec2(10, 10), 0.5);
    c.add_ink(glm::vec2(10, 0), glm::vec2(10, 64), 16.0);  // 1024 px^2 = 0.5 x 2048 terrain px
    c.update(4.0);
    EXPECT_NEAR(c.ink_share(), 1.0, 1e-9);
    EXPECT_NEAR(c.gain(glm::vec2(40, 40), 4.0), 1.0, 1e-9);
}
