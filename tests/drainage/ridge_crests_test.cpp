// Ridges moved onto the surface's crest (ridge_crests.hpp) on an analytic roof.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "drainage/dem_surface.hpp"
#include "drainage/ridge_crests.hpp"
#include "input/analytic_terrain.hpp"

namespace penink {
namespace {

constexpr double deg = 180.0 / std::numbers::pi;
const double crest_angle = 20.0 / deg;  // the crest's direction, off the grid's axes
const glm::dvec2 along{std::cos(crest_angle), std::sin(crest_angle)}, across{-along.y, along.x};

// Signed distance from the crest line through (0, 0).
double off_crest(double x, double y) { return x * across.x + y * across.y; }

// A roof of 10 m cells, falling 0.4 m a metre each side of a straight crest through the origin.
Terrain roof() {
    return terrain_from_function(81, 81, 10.0, [](double x, double y) { return 300.0 - 0.4 * std::abs(off_crest(x, y)); });
}

// The crest as a basin divide gives it: unit steps east and north on the dual grid (corners half
// a cell off the nodes), so 4 m or more off the crest and in long runs on the grid's axes.
DrapedLineSet staircase() {
    DrapedLineSet set;
    double x = -300.0 - 5.0, y = std::tan(crest_angle) * -300.0 + 5.0;
    for (int k = 0; k < 70; ++k) {
        set.vertices.push_back({float(x), float(y), 0.0f, 0.0f, 0.0f, 0.0f, 0.0f});
        // step north when the staircase falls a cell below the crest, else east
        if (off_crest(x + 10.0, y) < -5.0) y += 10.0;
        else x += 10.0;
    }
    set.lines.push_back({});
    set.lines[0].first = 0, set.lines[0].count = std::uint32_t(set.vertices.size());
    return set;
}

TEST(RidgeCrests, StaircaseDivideMovesOntoTheCrest) {
    const Terrain t = roof();
    const DemSurface surface(t);
    DrapedLineSet set = staircase();
    CrestOptions o;
    o.reach = 15.0, o.fade = 6, o.sigma = 2.0;  // a DEM cell and a half, as crest_options gives
    double before = 0.0;
    for (const DrapedVertex& v : set.vertices) before = std::max(before, std::abs(off_crest(v.x, v.y)));
    snap_to_crests(set, surface, o);
    // beyond the fade (the ends stay), every vertex within 1 m (a tenth of a cell: the parabola's
    // top on 5 m samples of a roof's kink, then the Gaussian) of the crest, and no segment more
    // than 5 degrees off its direction (the staircase's are 20 and 70)
    double worst = 0.0, worst_angle = 0.0;
    const std::size_t n = set.vertices.size();
    for (std::size_t k = std::size_t(o.fade) + 3; k + std::size_t(o.fade) + 3 < n; ++k) {
        const DrapedVertex &a = set.vertices[k - 1], &b = set.vertices[k];
        worst = std::max(worst, std::abs(off_crest(b.x, b.y)));
        const double dx = double(b.x) - a.x, dy = double(b.y) - a.y;
        worst_angle = std::max(worst_angle, std::acos(std::min(1.0, std::abs(dx * along.x + dy * along.y) / std::hypot(dx, dy))) * deg);
    }
    EXPECT_GT(before, 4.0);
    EXPECT_LT(worst, 1.0);
    EXPECT_LT(worst_angle, 5.0);
    // the ends stay where they were (the divides' junctions)
    const DrapedLineSet orig = staircase();
    EXPECT_EQ(set.vertices.front().x, orig.vertices.front().x);
    EXPECT_EQ(set.vertices.back().y, orig.vertices.back().y);
}

}  // namespace
}  // namespace penink
