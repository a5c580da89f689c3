// The chart's ray-cast reference (scene/raycast_reference.hpp) against the closed form
// (input/analytic_terrain.hpp): the visible contour generator of a Gaussian hill and of two hills
// one behind the other at grazing views, both scored at 1 px (lines/line_accuracy.hpp, the
// reference's split points rasterised at 1 px as drawn lines). Tolerance 1 px: the split points lie
// within 1/8 px of the PN surface's silhouette, which lies within ~0.2 px of the analytic one on a
// 25 m grid at these distances, and a 1-px raster adds up to 0.71 px.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "input/analytic_terrain.hpp"
#include "lines/line_accuracy.hpp"
#include "scene/raycast_reference.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;

namespace {

void expect_matches_closed_form(const char* name, double min_length) {
    const AnalyticCase c = *analytic_case(name, 400, 300);
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    const auto rays = raycast_reference(mesh, c.camera);
    const auto exact = analytic_silhouettes(c.shape, c.camera, false);
    const PixelMask drawn = rasterize_polylines(rays, c.camera.width, c.camera.height);
    const LineAccuracy a = line_accuracy(drawn, exact, {1.0});
    if (const char* dir = std::getenv("PENINK_DEBUG_PGM")) {  // ray-cast black, closed form white
        const PixelMask r = rasterize_polylines(exact, c.camera.width, c.camera.height);
        FILE* f = std::fopen((std::string(dir) + "/rays-" + name + ".pgm").c_str(), "wb");
        std::fprintf(f, "P5 %d %d 255\n", c.camera.width, c.camera.height);
        for (std::size_t i = 0; i < drawn.on.size(); ++i) std::fputc(r.on[i] ? 255 : drawn.on[i] ? 0 : 180, f);
        std::fclose(f);
    }
    std::printf("%s: ray-cast vs closed form: P1 %.3f R1 %.3f  d->r %.2f r->d %.2f px  ref %.0f px\n", name,
                a.at(1.0).precision, a.at(1.0).recall, a.mean_drawn_to_reference, a.mean_reference_to_drawn,
                a.reference_length);
    EXPECT_GT(a.reference_length, min_length);
    EXPECT_GE(a.at(1.0).precision, 0.95);
    EXPECT_GE(a.at(1.0).recall, 0.95);
}

}  // namespace

TEST(RaycastReference, MatchesTheClosedFormOnAGaussianHill) { expect_matches_closed_form("hill", 200.0); }

TEST(RaycastReference, MatchesTheClosedFormOnTwoHills) { expect_matches_closed_form("two-hills", 300.0); }
