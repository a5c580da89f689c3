// The reach of a stem from its network cells (stem_reach.hpp) holds the crease the whole build
// makes of it: every stem's built plan box lies in the plan box of its reach, on volcano at its
// automatic factor and at factor 1, on a DEM with nodata holes at factor 2 and on geographic
// jacksboro's curvilinear grid; the bound is not the whole DEM (its mean area over the DEM's:
// 0.27 on volcano at factor 5, where the margin of 20 DEM cells is a quarter of the DEM's width,
// 0.32 at factor 1, 0.33 with holes, 0.022 on jacksboro), and without the corridor's margin some
// traced creases leave their cells' boxes (77, 12 and 32 stems). The stems' bounds (the reach's
// box and crease_length_factor times the cells' plan length and rise, quantised) hold every crease's box and
// plan length and vertical travel, and quantise outward.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "line_test_dems.hpp"

#include "drainage/crease_tiles.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/stem_reach.hpp"
#include "input/dem_reader.hpp"

namespace penink {
namespace {

struct ReachCheck {
    std::size_t stems = 0, outside = 0;
    double area_share = 0.0;  // mean reach area over the DEM's plan box area
};

ReachCheck check_reach(const DrainageGrid& g, const DrainageResult& res, const DrainageDb& db, const FallLineOptions& o) {
    std::vector<std::uint32_t> cells;
    const DrapedLineSet walked = network_stems(g, res.dir, res.net, &cells);
    const PlanBoxes boxes(g);
    glm::vec2 all_lo, all_hi;
    boxes.plan_box(CellBox{0.0, 0.0, double(g.cols - 1), double(g.rows - 1)}, all_lo, all_hi);
    const double all = double(all_hi.x - all_lo.x) * double(all_hi.y - all_lo.y);
    ReachCheck c;
    EXPECT_EQ(walked.lines.size(), db.creases.lines.size());
    for (std::size_t s = 0; s < walked.lines.size() && s < db.creases.lines.size(); ++s) {
        const DrapedLine& l = walked.lines[s];
        glm::vec2 lo, hi;
        boxes.plan_box(stem_cell_reach(cells.data() + l.first, l.count, g, o), lo, hi);
        const DrapedLine& built = db.creases.lines[s];
        c.outside += !(built.lo.x >= lo.x && built.lo.y >= lo.y && built.hi.x <= hi.x && built.hi.y <= hi.y);
        c.area_share += double(hi.x - lo.x) * double(hi.y - lo.y) / all;
        ++c.stems;
    }
    c.area_share /= double(std::max<std::size_t>(1, c.stems));
    return c;
}

void expect_reach_holds(const Terrain& t, int factor, const std::string& what) {
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    ASSERT_FALSE(db.creases.lines.empty()) << what;
    const ReachCheck c = check_reach(g, res, db, fall_line_options(g));
    EXPECT_EQ(c.outside, 0u) << what;
    EXPECT_LT(c.area_share, 0.4) << what;
    // no margin: the cells' own box (and the reflections'), which traced creases leave
    FallLineOptions none = fall_line_options(g);
    none.max_corridor = -1.0;
    EXPECT_GT(check_reach(g, res, db, none).outside, 0u) << what;
    ::testing::Test::RecordProperty(what + "_mean_area_share_ppm", int(1e6 * c.area_share));
}

TEST(StemReach, CreasesLieInTheirReach) {
    for (const LineTestDem& dem : line_test_dems()) expect_reach_holds(dem.terrain, dem.factor, dem.name);
}

// Each stem's bound in the crease tiles' index (crease_tile_index: stem_bound of its reach and
// stem_cell_travel) holds the crease the whole build makes of it: the crease's box inside the
// bound's box, its plan length and vertical travel at most the bound's (so its length at any
// exaggeration e at most stem_bound_length), and its heights at most the index's z_top. The largest ratios of a crease's plan length over its
// cells' (1.18, jacksboro) and of its vertical travel over its cells' plus crease_rise_slope times
// their plan length (1.34, volcano at factor 5: a coarse PN surface bulges between its nodes) leave
// crease_length_factor and crease_rise_factor a margin of a fifth.
TEST(StemReach, BoundsHoldTheCreasesBoxAndLength) {
    for (const LineTestDem& dem : line_test_dems()) {
        DrainageGrid g = resample_pn(dem.terrain, dem.factor);
        DrainageResult res;
        const DrainageDb db = drainage_db_from_grid(g, {}, &res);
        const CreaseTileIndex index = crease_tile_index(g, res.dir, res.net);
        std::vector<std::uint32_t> cells;
        const DrapedLineSet walked = network_stems(g, res.dir, res.net, &cells);
        ASSERT_EQ(index.stems.size(), db.creases.lines.size()) << dem.name;
        ASSERT_EQ(walked.lines.size(), db.creases.lines.size()) << dem.name;
        std::size_t outside = 0, longer = 0, travel_differs = 0;
        double worst_plan = 0.0, worst_rise = 0.0, bound_sum = 0.0, length_sum = 0.0;
        for (std::size_t s = 0; s < index.stems.size(); ++s) {
            const DrapedLine& built = db.creases.lines[s];
            glm::vec2 lo, hi;
            stem_bound_box(index.stems[s], index.parts.lo, index.parts.hi, lo, hi);
            outside += !(built.lo.x >= lo.x && built.lo.y >= lo.y && built.hi.x <= hi.x && built.hi.y <= hi.y);
            double plan = 0.0, rise = 0.0;  // the built crease's
            for (std::uint32_t k = built.first + 1; k < built.first + built.count; ++k) {
                const DrapedVertex &a = db.creases.vertices[k - 1], &b = db.creases.vertices[k];
                plan += std::hypot(double(b.x) - double(a.x), double(b.y) - double(a.y));
                rise += std::abs(double(b.z) - double(a.z));
            }
            longer += plan > stem_bound_plan(index.stems[s]) || rise > stem_bound_rise(index.stems[s]) ||
                      double(built.length) > stem_bound_length(index.stems[s], 1.0);
            const StemTravel t = stem_cell_travel(cells.data() + walked.lines[s].first, walked.lines[s].count, g);
            // given the walk's x, y (what the index's walk passes), the same sums bit for bit: at
            // factor 1 read instead of grid_xy, whose values they are; ignored at other factors
            std::vector<glm::vec2> xy;
            for (std::uint32_t k = 0; k < walked.lines[s].count; ++k) {
                const DrapedVertex& v = walked.vertices[walked.lines[s].first + k];
                xy.emplace_back(v.x, v.y);
            }
            const StemTravel given = stem_cell_travel(cells.data() + walked.lines[s].first, walked.lines[s].count, g, xy.data());
            if (given.plan != t.plan || given.rise != t.rise) ++travel_differs;
            if (t.plan > 0.0) {
                worst_plan = std::max(worst_plan, plan / t.plan);
                worst_rise = std::max(worst_rise, rise / (t.rise + crease_rise_slope * t.plan));
            } else {
                EXPECT_EQ(built.length, 0.0f) << dem.name << " stem " << s;
            }
            bound_sum += stem_bound_length(index.stems[s], 1.0), length_sum += built.length;
        }
        EXPECT_EQ(outside, 0u) << dem.name;
        EXPECT_EQ(longer, 0u) << dem.name;
        EXPECT_EQ(travel_differs, 0u) << dem.name;
        // no crease vertex above the drape's height bound, which is no more than the highest node
        // plus the relief (the longest edge's rise) and a few cells
        float z_max = -1e30f, z_lo = 1e30f;
        for (const DrapedVertex& v : db.creases.vertices) z_max = std::max(z_max, v.z);
        for (std::size_t i = 0; i < g.size(); ++i)
            if (g.valid[i]) z_lo = std::min(z_lo, g.z[i]);
        EXPECT_LE(z_max, index.z_top) << dem.name;
        EXPECT_LT(index.z_top, z_max + 2.0f * (z_max - z_lo)) << dem.name;
        EXPECT_GT(worst_plan, 1.0) << dem.name;  // the cells' plan length alone is no bound
        EXPECT_LE(1.2 * worst_plan, crease_length_factor) << dem.name;
        EXPECT_LE(1.2 * worst_rise, crease_rise_factor) << dem.name;
        ::testing::Test::RecordProperty(dem.name + "_worst_plan_ratio_ppm", int(1e6 * worst_plan));
        ::testing::Test::RecordProperty(dem.name + "_worst_rise_ratio_ppm", int(1e6 * worst_rise));
        ::testing::Test::RecordProperty(dem.name + "_bound_over_length_ppm", int(1e6 * bound_sum / length_sum));
    }
}

// The quantised bound holds the box and length it is made from, within a step of the grid across
// the stems' box (and a float's rounding) and a 128th of the length; an empty reach gives an
// empty box, a reach beyond the stems' box is cut to it.
TEST(StemReach, BoundsQuantiseOutward) {
    const glm::vec2 lo(-1234.5f, 250.25f), hi(8765.5f, 4321.0f);
    const glm::vec2 step = (hi - lo) / 65535.0f;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < 20000; ++k) {
        glm::vec2 a = lo + glm::vec2(u(rng), u(rng)) * (hi - lo), b = lo + glm::vec2(u(rng), u(rng)) * (hi - lo);
        const glm::vec2 rlo = glm::min(a, b), rhi = glm::max(a, b);
        const StemTravel t{1e4 * double(u(rng)) * double(u(rng)), 1e3 * double(u(rng)) * double(u(rng))};
        const StemBound sb = stem_bound(rlo, rhi, t, lo, hi);
        glm::vec2 blo, bhi;
        stem_bound_box(sb, lo, hi, blo, bhi);
        ASSERT_TRUE(blo.x <= rlo.x && blo.y <= rlo.y && bhi.x >= rhi.x && bhi.y >= rhi.y) << k;
        ASSERT_TRUE(rlo.x - blo.x <= 1.01f * step.x + 1e-3f && bhi.y - rhi.y <= 1.01f * step.y + 1e-3f) << k;
        const double plan = crease_length_factor * t.plan;
        const double rise = crease_rise_factor * (t.rise + crease_rise_slope * t.plan);
        ASSERT_GE(stem_bound_plan(sb), plan) << k;
        ASSERT_LE(stem_bound_plan(sb), plan * (1.0 + 1.0 / 128.0) + 1e-30) << k;
        ASSERT_GE(stem_bound_rise(sb), rise) << k;
        ASSERT_LE(stem_bound_rise(sb), rise * (1.0 + 1.0 / 128.0) + 1e-30) << k;
        ASSERT_EQ(stem_bound_length(sb, 2.0), double(stem_bound_plan(sb)) + 2.0 * double(stem_bound_rise(sb))) << k;
    }
    glm::vec2 blo, bhi;
    stem_bound_box(stem_bound(glm::vec2(1.0f), glm::vec2(0.0f), StemTravel{1.0, 0.0}, lo, hi), lo, hi, blo, bhi);
    EXPECT_TRUE(bhi.x < blo.x);
    stem_bound_box(stem_bound(lo - 100.0f, hi + 100.0f, StemTravel{1.0, 0.0}, lo, hi), lo, hi, blo, bhi);
    EXPECT_EQ(blo, lo);
    EXPECT_EQ(bhi, hi);
}

}  // namespace
}  // namespace penink

namespace penink {
namespace {

// PlanBoxes on a grid that is not affine (geographic jacksboro at factor 1): for index boxes of
// every size from a cell to most of the grid at seeded random places, the box of the nodes of
// every 8 x 8 block that meets the box's node range, rounded outward to floats, as the blocks
// alone gave it before windows of 4 x 4 blocks answered the larger ones: the same floats.
TEST(StemReach, PlanBoxesOfWindowsAreThoseOfTheirBlocks) {
    {
        const DrainageGrid g = resample_pn(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 1);
        ASSERT_FALSE(g.has_affine);
        const PlanBoxes boxes(g);
        std::mt19937 rng(11);
        std::size_t windows = 0, bad = 0;
        for (int k = 0; k < 3000; ++k) {
            const double side = std::exp(std::uniform_real_distribution<double>(0.0, std::log(0.8 * g.cols))(rng));
            const double c0 = std::uniform_real_distribution<double>(-2.0, g.cols - side)(rng),
                         r0 = std::uniform_real_distribution<double>(-2.0, g.rows - side * 0.7)(rng);
            const CellBox b{std::max(0.0, c0), std::max(0.0, r0), std::min(g.cols - 1.0, c0 + side),
                            std::min(g.rows - 1.0, r0 + side * 0.7)};
            if (b.c1 < b.c0 || b.r1 < b.r0) continue;
            glm::vec2 lo, hi;
            boxes.plan_box(b, lo, hi);
            // the blocks' way: every node of the blocks meeting the node range
            const int nc0 = std::clamp(int(std::floor(b.c0)) - 1, 0, g.cols - 1), nc1 = std::clamp(int(std::floor(b.c1)) + 2, 0, g.cols - 1);
            const int nr0 = std::clamp(int(std::floor(b.r0)) - 1, 0, g.rows - 1), nr1 = std::clamp(int(std::floor(b.r1)) + 2, 0, g.rows - 1);
            windows += nc1 / 8 - nc0 / 8 >= 3 && nr1 / 8 - nr0 / 8 >= 3;
            glm::dvec2 l(1e300), h(-1e300);
            for (int r = nr0 / 8 * 8; r < std::min(g.rows, (nr1 / 8 + 1) * 8); ++r)
                for (int c = nc0 / 8 * 8; c < std::min(g.cols, (nc1 / 8 + 1) * 8); ++c) {
                    const glm::dvec2 p = grid_xy(g, c, r);
                    l = glm::min(l, p), h = glm::max(h, p);
                }
            const float inf = std::numeric_limits<float>::infinity();
            const glm::vec2 want_lo(std::nextafter(float(l.x), -inf), std::nextafter(float(l.y), -inf));
            const glm::vec2 want_hi(std::nextafter(float(h.x), inf), std::nextafter(float(h.y), inf));
            bad += lo != want_lo || hi != want_hi;
        }
        EXPECT_EQ(bad, 0u);
        EXPECT_GT(windows, 1000u);
    }
}

}  // namespace
}  // namespace penink
