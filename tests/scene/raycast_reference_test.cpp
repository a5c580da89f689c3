// The chart's ray-cast reference (scene/raycast_reference.hpp) against the closed form
// (input/analytic_terrain.hpp): the visible contour generator of a Gaussian hill and of two hills
// one behind the other at grazing views. Recall: the closed form's length within 1 px of the
// ray-cast lines rasterised at 1 px (lines/line_accuracy.hpp; the raster adds up to 0.71 px).
// Precision, on the lines themselves: the ray-cast length within 0.5 px of the closed form (split
// points lie within 1/8 px of the PN surface's silhouette, which lies within ~0.2 px of the
// analytic one on a 25 m grid at these distances).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "input/analytic_terrain.hpp"
#include "lines/line_accuracy.hpp"
#include "lines/object_silhouettes.hpp"
#include "surface/pn_tessellation.hpp"
#include "scene/raycast_reference.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;

namespace {

// Distance from p to the nearest segment of the polylines, pixels.
double distance_to(const std::vector<std::vector<glm::vec2>>& lines, glm::vec2 p) {
    double best = 1e30;
    for (const auto& line : lines)
        for (std::size_t i = 1; i < line.size(); ++i) {
            const glm::dvec2 a(line[i - 1]), ab = glm::dvec2(line[i]) - a, ap = glm::dvec2(p) - a;
            const double t = glm::dot(ab, ab) > 0 ? std::clamp(glm::dot(ap, ab) / glm::dot(ab, ab), 0.0, 1.0) : 0.0;
            best = std::min(best, glm::length(ap - t * ab));
        }
    return best;
}

void expect_matches_closed_form(const char* name, double min_length, double min_precision) {
    const AnalyticCase c = *analytic_case(name, 400, 300);
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    const auto rays = raycast_reference(mesh, c.camera);
    const auto exact = analytic_silhouettes(c.shape, c.camera, false);
    const PixelMask drawn = rasterize_polylines(rays, c.camera.width, c.camera.height);
    const LineAccuracy a = line_accuracy(drawn, exact, {1.0});
    double near = 0, length = 0;  // ray-cast length within 0.5 px of the closed form
    for (const auto& line : rays)
        for (std::size_t i = 1; i < line.size(); ++i) {
            const double l = glm::length(line[i] - line[i - 1]);
            length += l;
            if (distance_to(exact, 0.5f * (line[i] + line[i - 1])) <= 0.5) near += l;
        }
    const double precision = length > 0 ? near / length : 1.0;
    if (const char* dir = std::getenv("PENINK_DEBUG_PGM")) {  // ray-cast black, closed form white
        const PixelMask r = rasterize_polylines(exact, c.camera.width, c.camera.height);
        FILE* f = std::fopen((std::string(dir) + "/rays-" + name + ".pgm").c_str(), "wb");
        std::fprintf(f, "P5 %d %d 255\n", c.camera.width, c.camera.height);
        for (std::size_t i = 0; i < drawn.on.size(); ++i) std::fputc(r.on[i] ? 255 : drawn.on[i] ? 0 : 180, f);
        std::fclose(f);
    }
    std::printf("%s: ray-cast vs closed form: length within 0.5 px %.3f (raster P1 %.3f), R1 %.3f  r->d %.2f px  "
                "ref %.0f px\n", name, precision, a.at(1.0).precision, a.at(1.0).recall, a.mean_reference_to_drawn,
                a.reference_length);
    EXPECT_GT(a.reference_length, min_length);
    EXPECT_GE(precision, min_precision);
    EXPECT_GE(a.at(1.0).recall, 0.95);
}

}  // namespace

// Measured 0.938 within 0.5 px (0.936 of the raster within 1 px): the rest are a few short pieces
// on the lower flanks, seen in the debug image (PENINK_DEBUG_PGM=DIR), where the grazing contour
// of the PN surface of the 25 m grid strays from the Gaussian's (next test).
TEST(RaycastReference, MatchesTheClosedFormOnAGaussianHill) { expect_matches_closed_form("hill", 200.0, 0.9); }

TEST(RaycastReference, MatchesTheClosedFormOnTwoHills) { expect_matches_closed_form("two-hills", 300.0, 0.95); }

// Where the ray-cast reference strays from the Gaussian's closed form it follows the PN surface's
// own contour: the ray-cast length farther than 0.5 px from the closed form lies within 0.25 px of
// the visible object-space silhouette edges (front/back edges, lines/object_silhouettes.hpp) of
// the same tessellation, a method that shares no code with the ray casting. Measured: all of it
// (15.9 px of 231); so the reference is right about the surface it samples, and the strays are
// where the PN interpolation of the 25 m grid folds where the Gaussian does not.
TEST(RaycastReference, StrayPiecesFollowTheTessellatedSurfacesContour) {
    const AnalyticCase c = *analytic_case("hill", 400, 300);
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    const RaycastReferenceOptions o;
    const float s = float(o.rays.supersample);
    const PnTessellation tess = tessellate_pn_surface(mesh, view_projection(c.camera),
                                                      glm::vec2(c.camera.width * s, c.camera.height * s), o.edge_px * s, 64);
    const auto rays = raycast_reference(mesh, c.camera, o);
    const auto exact = analytic_silhouettes(c.shape, c.camera, false);
    const auto contour = silhouette_polylines(object_space_silhouettes(tess.pos, tess.tri, c.camera), false);
    double stray = 0, on_contour = 0;
    for (const auto& line : rays)
        for (std::size_t i = 1; i < line.size(); ++i) {
            const glm::vec2 m = 0.5f * (line[i] + line[i - 1]);
            if (distance_to(exact, m) <= 0.5) continue;
            const double l = glm::length(line[i] - line[i - 1]), d = distance_to(contour, m);
            stray += l;
            if (d <= 0.25) on_contour += l;
        }
    std::printf("hill: ray-cast length off the closed form %.1f px, of it within 0.25 px of the mesh contour %.1f px\n",
                stray, on_contour);
    ASSERT_GT(stray, 0.0);
    EXPECT_GE(on_contour / stray, 0.9);
}
