// Direction measures of plan polylines (stroke_directions.hpp) on analytic terrains.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "input/analytic_terrain.hpp"
#include "lines/stroke_directions.hpp"

namespace penink {
namespace {

constexpr double rad = std::numbers::pi / 180.0;

// Parallel straight lines at `angle_deg` (from east, counterclockwise) through the middle of a
// 400 m square, each cut into 2 m segments.
std::vector<std::vector<glm::dvec2>> parallel_lines(double angle_deg) {
    const glm::dvec2 d(std::cos(angle_deg * rad), std::sin(angle_deg * rad)), n(-d.y, d.x);
    std::vector<std::vector<glm::dvec2>> out;
    for (int i = -5; i <= 5; ++i) {
        std::vector<glm::dvec2> l;
        for (int k = -50; k <= 50; ++k) l.push_back(20.0 * i * n + 2.0 * k * d);
        out.push_back(l);
    }
    return out;
}

// A plane falling towards azimuth 30 degrees (from east) at `slope_deg`, 10 m cells.
Terrain plane(double slope_deg) {
    const double g = std::tan(slope_deg * rad);
    return terrain_from_function(61, 61, 10.0, [g](double x, double y) {
        return 500.0 - g * (std::cos(30.0 * rad) * x + std::sin(30.0 * rad) * y);
    });
}

TEST(StrokeDirections, FallLinesOnAPlane) {
    const FallLineField field(plane(20.0));
    // along the fall line: no grid run, 0 degrees (finite differences of a plane are exact; the
    // floats of the node positions leave well under 0.01 degree)
    const StrokeDirections along = stroke_directions(parallel_lines(210.0), field);
    EXPECT_EQ(along.grid_length, 0.0);
    EXPECT_GT(along.sloped_segments, 1000u);
    EXPECT_LT(along.fall_median_deg, 0.01);
    EXPECT_LT(along.fall_p90_deg, 0.01);
    // across it: 90 degrees
    EXPECT_NEAR(stroke_directions(parallel_lines(120.0), field).fall_median_deg, 90.0, 0.01);
    // along a diagonal of the grid: all of it in grid runs, 15 degrees off the fall line
    const StrokeDirections diagonal = stroke_directions(parallel_lines(45.0), field);
    EXPECT_NEAR(diagonal.grid_share(), 1.0, 1e-12);
    EXPECT_NEAR(diagonal.fall_median_deg, 15.0, 0.01);
    // 1.5 degrees off a grid axis: outside the 1 degree tolerance; 0.5 degrees: inside
    EXPECT_EQ(stroke_directions(parallel_lines(1.5), field).grid_share(), 0.0);
    EXPECT_NEAR(stroke_directions(parallel_lines(90.5), field).grid_share(), 1.0, 1e-12);
}

TEST(StrokeDirections, GentleSlopesAreLeftOutOfTheFallLineAngles) {
    const StrokeDirections d = stroke_directions(parallel_lines(120.0), FallLineField(plane(4.0)));
    EXPECT_EQ(d.sloped_segments, 0u);
    EXPECT_GT(d.length, 1000.0);
}

TEST(StrokeDirections, GridDirectionsAreTheCellsOwn) {
    // cells 10 m east by 5 m south (as a UTM-projected geographic grid's are not square): the
    // diagonals run at atan(5 / 10) = 26.57 degrees, and 45 degrees is no grid direction
    Terrain t = terrain_from_function(61, 61, 10.0, [](double x, double) { return 0.3 * x; });
    for (glm::vec3& p : t.pos) p.y *= 0.5f;
    const FallLineField field(t);
    EXPECT_NEAR(stroke_directions(parallel_lines(std::atan(0.5) / rad), field).grid_share(), 1.0, 1e-12);
    EXPECT_EQ(stroke_directions(parallel_lines(45.0), field).grid_share(), 0.0);
    EXPECT_NEAR(stroke_directions(parallel_lines(-90.0), field).grid_share(), 1.0, 1e-12);
}

}  // namespace
}  // namespace penink
