// The chart's ray-cast reference (scene/raycast_reference.hpp) against the closed form
// (input/analytic_terrain.hpp): the visible contour generator of a Gaussian hill and of two hills
// one behind the other at grazing views, both scored at 1 px (lines/line_accuracy.hpp, the
// reference's split points rasterised at 1 px as drawn lines). Tolerance 1 px: the split points lie
// within 1/8 px of the PN surface's silhouette, which lies within ~0.2 px of the analytic one on a
// 25 m grid at these distances, and a 1-px raster adds up to 0.71 px.
#include <cstdio>

#include <gtest/gtest.h>

#include "input/analytic_terrain.hpp"
#include "lines/line_accuracy.hpp"
#include "scene/raycast_reference.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;

namespace {

void expect_matches_closed_form(const AnalyticTerrain& s, const Camera& cam, double min_length) {
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(s, 25.0));
    const auto rays = raycast_reference(mesh, cam);
    const auto exact = analytic_silhouettes(s, cam, false);
    const LineAccuracy a = line_accuracy(rasterize_polylines(rays, cam.width, cam.height), exact, {1.0});
    std::printf("ray-cast vs closed form: P1 %.3f R1 %.3f  d->r %.2f r->d %.2f px  ref %.0f px\n", a.at(1.0).precision,
                a.at(1.0).recall, a.mean_drawn_to_reference, a.mean_reference_to_drawn, a.reference_length);
    EXPECT_GT(a.reference_length, min_length);
    EXPECT_GE(a.at(1.0).precision, 0.95);
    EXPECT_GE(a.at(1.0).recall, 0.95);
}

Camera camera(glm::dvec3 eye, double altitude, double top, const AnalyticTerrain& s) {
    Camera c;
    c.eye = eye, c.azimuth = 0.0, c.altitude = altitude, c.fov = 40.0;
    c.width = 400, c.height = 300;
    fit_depth_range(c, {-s.half_extent, -s.half_extent, 0.0}, {s.half_extent, s.half_extent, top});
    return c;
}

}  // namespace

TEST(RaycastReference, MatchesTheClosedFormOnAGaussianHill) {
    AnalyticTerrain s;  // 250 m high, sigma 150 m
    expect_matches_closed_form(s, camera({0.0, -1300.0, 450.0}, -10.0, 250.0, s), 200.0);
}

TEST(RaycastReference, MatchesTheClosedFormOnTwoHills) {
    AnalyticTerrain s;
    s.shape = AnalyticShape::two_hills, s.half_extent = 3000.0;
    expect_matches_closed_form(s, camera({0.0, -1300.0, 700.0}, -14.0, 400.0, s), 300.0);
}
