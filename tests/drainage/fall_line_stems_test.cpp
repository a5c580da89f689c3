// Creases along the fall line (fall_line_stems.hpp) on analytic terrains.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/fall_line_stems.hpp"
#include "input/analytic_terrain.hpp"

namespace penink {
namespace {

constexpr double deg = 180.0 / std::numbers::pi;

// Length-weighted quantile q of (angle, length) pairs.
double quantile(std::vector<std::pair<double, double>> v, double q) {
    std::sort(v.begin(), v.end());
    double total = 0.0, acc = 0.0;
    for (const auto& a : v) total += a.second;
    for (const auto& a : v)
        if ((acc += a.second) >= q * total) return a.first;
    return v.empty() ? 0.0 : v.back().first;
}

// Angles (degrees, 0-90) of the segments to the direction from the origin, with their lengths,
// for segments from r0 to r1 from it.
std::vector<std::pair<double, double>> radial_angles(const DrapedLineSet& set, double r0, double r1 = 1e30) {
    std::vector<std::pair<double, double>> out;
    for (const DrapedLine& l : set.lines)
        for (std::uint32_t k = 1; k < l.count; ++k) {
            const DrapedVertex &a = set.vertices[l.first + k - 1], &b = set.vertices[l.first + k];
            const glm::dvec2 d(double(b.x) - a.x, double(b.y) - a.y);
            const glm::dvec2 m = 0.5 * glm::dvec2(double(a.x) + b.x, double(a.y) + b.y);
            const double len = std::hypot(d.x, d.y), rm = std::hypot(m.x, m.y);
            if (len < 1e-6 || rm < r0 || rm > r1) continue;
            out.emplace_back(std::acos(std::min(1.0, std::abs(d.x * m.x + d.y * m.y) / (len * rm))) * deg, len);
        }
    return out;
}

struct Cone {
    DrainageGrid g;
    DrainageResult res;
    Cone() {
        // 60 x 60 nodes of 10 m, 0.5 m fall a metre from the apex at the origin: every fall line is
        // radial, while D8 paths on it run in the 8 grid directions, up to 22.5 degrees off
        const Terrain t = terrain_from_function(60, 60, 10.0, [](double x, double y) { return 400.0 - 0.5 * std::hypot(x, y); });
        g = resample_pn(t, 5);
        drainage_db_from_grid(g, {}, &res);
    }
    DrapedLineSet stems(std::vector<std::uint32_t>& cells) const { return network_stems(g, res.dir, res.net, &cells); }
    // Its stems as D8 paths and traced with the build's options: smoothed as the build does
    // (smooth_stems: the trace, then the ends) or only traced (trace_fall_lines).
    std::pair<DrapedLineSet, DrapedLineSet> d8_and_traced(bool smooth) const {
        std::vector<std::uint32_t> cells;
        std::pair<DrapedLineSet, DrapedLineSet> out{stems(cells), DrapedLineSet{}};
        out.second = out.first;
        if (smooth) smooth_stems(out.second, cells, g, fall_line_options(g));
        else trace_fall_lines(out.second, cells, g, fall_line_options(g));
        return out;
    }
};

TEST(FallLineStems, ConeCreasesAreRadialWithTheBuildsOptions) {
    // what build_draped_lines does: the trace with the build's options, then the ends
    const auto [d8, traced] = Cone().d8_and_traced(true);
    // the apex's neighbourhood (where one cell spans a large angle) left out: 30 m
    const auto before = radial_angles(d8, 30.0), after = radial_angles(traced, 30.0);
    ASSERT_GT(after.size(), 10000u);
    // D8: about 10 degrees off radial at the median; traced: within 2 degrees at the median (the
    // fall line comes from the DEM's 10 m nodes' central differences, bilinear, which bend it by
    // well under a degree at 30 m and more from the apex)
    EXPECT_GT(quantile(before, 0.5), 5.0);
    EXPECT_LT(quantile(after, 0.5), 2.0);
    // inside 250 m (the D8 network's trunks run along the DEM's edge, 295 m out, and collect
    // every other stem there): within 2 degrees for all of the length; the tributaries whose
    // fall line leads away from their junction on those trunks end on their fall line instead
    // of bending back to it (D8 paths merge where a cone's fall lines never do)
    const auto inner = radial_angles(traced, 30.0, 250.0);
    std::printf("cone: radial angle quantiles 0.5 %.2f, 0.8 %.2f, 0.99 %.2f, 1 %.2f deg\n", quantile(inner, 0.5),
                quantile(inner, 0.8), quantile(inner, 0.99), quantile(inner, 1.0));
    EXPECT_LT(quantile(inner, 0.5), 2.0);
    EXPECT_LT(quantile(inner, 1.0), 2.0);
    // the stems keep their vertices, sources and flow
    ASSERT_EQ(traced.vertices.size(), d8.vertices.size());
    for (const DrapedLine& l : d8.lines) {
        EXPECT_EQ(traced.vertices[l.first].x, d8.vertices[l.first].x);
        EXPECT_EQ(traced.vertices[l.first].y, d8.vertices[l.first].y);
        EXPECT_EQ(traced.vertices[l.first + l.count - 1].flow, d8.vertices[l.first + l.count - 1].flow);
    }
}

TEST(FallLineStems, NarrowCorridorHoldsConeCreasesToTheirD8Paths) {
    const Cone cone;
    std::vector<std::uint32_t> cells;
    const DrapedLineSet d8 = cone.stems(cells);
    DrapedLineSet traced = d8;
    FallLineOptions o = fall_line_options(cone.g);
    o.widen = 0.0;  // the corridor stays 3 cells wide: the D8 paths' bias stays
    trace_fall_lines(traced, cells, cone.g, o);
    EXPECT_GT(quantile(radial_angles(traced, 30.0), 0.9), 2.0);
}

TEST(FallLineStems, TracedStemsStayInTheirCorridor) {
    const Cone cone;
    std::vector<std::uint32_t> cells;
    const DrapedLineSet d8 = cone.stems(cells);
    DrapedLineSet traced = d8;
    const FallLineOptions o = fall_line_options(cone.g);
    trace_fall_lines(traced, cells, cone.g, o);
    // each vertex within the widest corridor (cells of 2 m) plus the centre line's own smoothing
    // of the D8 path (a Gaussian of sigma cells moves a path corner by under sigma) of its D8 cell
    const double cell = 2.0, bound = (o.max_corridor + o.sigma) * cell + 1e-3;
    // (vertices after a trace stopped at the grid's edge stay there: left out)
    double worst = 0.0;
    for (const DrapedLine& l : d8.lines)
        for (std::uint32_t k = 0; k < l.count; ++k) {
            const std::size_t i = l.first + k;
            if (k > 0 && traced.vertices[i].x == traced.vertices[i - 1].x && traced.vertices[i].y == traced.vertices[i - 1].y) break;
            worst = std::max(worst, double(std::hypot(traced.vertices[i].x - d8.vertices[i].x, traced.vertices[i].y - d8.vertices[i].y)));
        }
    EXPECT_LE(worst, bound);
    EXPECT_GT(worst, 2.0 * o.corridor * cell);  // the cone's fall lines leave the D8 cells well beyond the corridor at the source
}

// Of the stem ends that sat on another line's interior vertex before smooth_stems (`matched`),
// those that end within `meet` (plan units) of a vertex of that line after it.
// Junctions farther than y_band from y = 0 are left out.
std::size_t ends_at_their_trunk(const DrapedLineSet& before, const DrapedLineSet& after, double meet, std::size_t* matched,
                                double y_band = 1e30) {
    std::size_t near = 0;
    *matched = 0;
    for (const DrapedLine& l : before.lines) {
        const DrapedVertex& e = before.vertices[l.first + l.count - 1];
        if (std::abs(e.y) > y_band) continue;
        const DrapedVertex& a = after.vertices[l.first + l.count - 1];
        for (const DrapedLine& m : before.lines) {
            if (&m == &l) continue;
            bool sat = false;
            for (std::uint32_t k = 1; k + 1 < m.count; ++k)
                sat |= before.vertices[m.first + k].x == e.x && before.vertices[m.first + k].y == e.y;
            if (!sat) continue;
            ++*matched;
            double best = 1e300;
            for (std::uint32_t k = 0; k < m.count; ++k)
                best = std::min(best, double(std::hypot(after.vertices[m.first + k].x - a.x, after.vertices[m.first + k].y - a.y)));
            near += best <= meet;
            break;
        }
    }
    return near;
}

// A V-shaped valley (sides falling 0.3 m a metre to its floor, the floor 0.05 m a metre): the
// side slopes' fall lines all reach the floor, so every tributary ends at its trunk (within the
// meeting distance, one DEM cell) and none runs on beside it.
TEST(FallLineStems, TributariesWhoseFallLineReachesTheFloorJoinIt) {
    const Terrain t = terrain_from_function(40, 60, 10.0, [](double x, double y) { return 300.0 + 0.3 * std::abs(x) + 0.05 * y; });
    DrainageGrid g = resample_pn(t, 3);
    DrainageResult res;
    drainage_db_from_grid(g, {}, &res);
    std::vector<std::uint32_t> cells;
    const DrapedLineSet d8 = network_stems(g, res.dir, res.net, &cells);
    DrapedLineSet traced = d8;
    const FallLineOptions o = fall_line_options(g);
    smooth_stems(traced, cells, g, o);
    std::size_t matched = 0;
    const double cell = 10.0 / 3.0;
    // (junctions within 100 m of the DEM's lower and upper edges left out: the fall lines of the
    // slopes above the lower ones leave the DEM before they reach the floor, and those stems
    // stop there; the upper ones join stems of two vertices, which are not traced)
    EXPECT_EQ(ends_at_their_trunk(d8, traced, o.meet * cell + 1e-3, &matched, 195.0), matched);
    ASSERT_GT(matched, 20u);
}

// On the cone the D8 paths merge along the DEM's edge where the fall lines never do: most
// tributaries end where their trace ends instead of bending back (those traced beside their
// trunk end where they meet it).
TEST(FallLineStems, TributariesWhoseFallLineLeadsElsewhereEndOnIt) {
    const Cone cone;
    const auto [d8, traced] = cone.d8_and_traced(true);
    const FallLineOptions o = fall_line_options(cone.g);
    std::size_t matched = 0;
    const std::size_t near = ends_at_their_trunk(d8, traced, o.meet * 2.0 + 1e-3, &matched);
    std::printf("cone: %zu of %zu tributaries end at their trunk\n", near, matched);
    ASSERT_GT(matched, 100u);
    EXPECT_LT(near, matched / 2);
}

// A trace that reaches the grid's edge stops there: no vertex jumps back to the D8 path's centre
// line, so no segment of a stem is longer than a few cells.
TEST(FallLineStems, TracesStopAtTheGridsEdge) {
    const auto traced = Cone().d8_and_traced(false).second;
    double longest = 0.0;
    for (const DrapedLine& l : traced.lines)
        for (std::uint32_t k = 1; k < l.count; ++k) {
            const DrapedVertex &a = traced.vertices[l.first + k - 1], &b = traced.vertices[l.first + k];
            longest = std::max(longest, double(std::hypot(b.x - a.x, b.y - a.y)));
        }
    EXPECT_LT(longest, 2.0 * 2.0 * std::sqrt(2.0));  // two diagonal cells of 2 m
}

}  // namespace
}  // namespace penink
