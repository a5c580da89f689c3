// Creases along the fall line (fall_line_stems.hpp) on analytic terrains.
#include <algorithm>
#include <cmath>
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
};

TEST(FallLineStems, ConeCreasesAreRadialWithTheBuildsOptions) {
    const Cone cone;
    std::vector<std::uint32_t> cells;
    const DrapedLineSet d8 = cone.stems(cells);
    DrapedLineSet traced = d8;
    // what build_draped_lines does: the trace with the build's options, then the ends joined
    smooth_stems(traced, cells, cone.g, fall_line_options(cone.g));
    // the apex's neighbourhood (where one cell spans a large angle) left out: 30 m
    const auto before = radial_angles(d8, 30.0), after = radial_angles(traced, 30.0);
    ASSERT_GT(after.size(), 10000u);
    // D8: about 10 degrees off radial at the median; traced: within 2 degrees at the median (the
    // fall line comes from the DEM's 10 m nodes' central differences, bilinear, which bend it by
    // well under a degree at 30 m and more from the apex)
    EXPECT_GT(quantile(before, 0.5), 5.0);
    EXPECT_LT(quantile(after, 0.5), 2.0);
    // inside 250 m (the D8 network's trunks run along the DEM's edge, 295 m out, and collect
    // every other stem there): within 2 degrees for 80 % of the length; the rest are the
    // tributaries' bends back to those junctions, which the network keeps (D8 paths merge where
    // a cone's fall lines never do)
    const auto inner = radial_angles(traced, 30.0, 250.0);
    EXPECT_LT(quantile(inner, 0.5), 2.0);
    EXPECT_LT(quantile(inner, 0.8), 2.0);
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
    double worst = 0.0;
    for (std::size_t i = 0; i < d8.vertices.size(); ++i)
        worst = std::max(worst, double(std::hypot(traced.vertices[i].x - d8.vertices[i].x, traced.vertices[i].y - d8.vertices[i].y)));
    EXPECT_LE(worst, bound);
    EXPECT_GT(worst, 2.0 * o.corridor * cell);  // the cone's fall lines leave the D8 cells well beyond the corridor at the source
}

// A stem ending at a junction comes back to it: traced with its end marked joined, the last
// vertex is within the corridor at the source of its D8 cell however far the corridor widened.
TEST(FallLineStems, JoinedEndsComeBackToTheirJunction) {
    const Cone cone;
    std::vector<std::uint32_t> cells;
    const DrapedLineSet d8 = cone.stems(cells);
    DrapedLineSet free_end = d8, joined_end = d8;
    const FallLineOptions o = fall_line_options(cone.g);
    trace_fall_lines(free_end, cells, cone.g, o);
    trace_fall_lines(joined_end, cells, cone.g, o, std::vector<std::uint8_t>(d8.lines.size(), 1));
    const double cell = 2.0;
    double free_worst = 0.0, joined_worst = 0.0;
    for (const DrapedLine& l : d8.lines) {
        const std::uint32_t e = l.first + l.count - 1;
        const auto gap = [&](const DrapedLineSet& s) {
            return double(std::hypot(s.vertices[e].x - d8.vertices[e].x, s.vertices[e].y - d8.vertices[e].y));
        };
        free_worst = std::max(free_worst, gap(free_end)), joined_worst = std::max(joined_worst, gap(joined_end));
    }
    EXPECT_GT(free_worst, 3.0 * o.corridor * cell);
    EXPECT_LE(joined_worst, (o.corridor + o.sigma) * cell + 1e-3);
}

}  // namespace
}  // namespace penink
