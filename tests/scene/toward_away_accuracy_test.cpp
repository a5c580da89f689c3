// Toward/Away silhouettes (Mower, "Fast Image-Space Silhouette Extraction", sec. 3.2) against the
// closed form on three analytic terrains of input/analytic_terrain.hpp, each at a grazing view:
// two Gaussian hills one behind the other (the near one hides the far one's foot: T-junctions),
// a steep smooth cliff seen from its high side, and a col between two peaks (a saddle). The
// reference is the visible part of the contour generator n . (eye - p) = 0 of the analytic
// surface (visibility ray-marched against the closed form). Both the SIL mask and the drawn
// strokes (traced and simplified, scene/terrain_frames.hpp) are scored at 1.5 px
// (lines/line_accuracy.hpp): precision = drawn pixels within 1.5 px of the reference, recall =
// reference length within 1.5 px of a drawn pixel centre.
// Tolerance 1.5 px: a drawn pixel centre is up to 0.71 px from the curve it marks, plus the PN
// surface's departure from the analytic one (grids 5-25 m: < 0.2 px at these distances).
#include <cstdio>

#include <gtest/gtest.h>

#include "input/analytic_terrain.hpp"
#include "lines/line_accuracy.hpp"
#include "render/terrain_renderer.hpp"
#include "scene/terrain_frames.hpp"
#include "support/gl_test_context.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;

namespace {

struct Case {
    const char* name;
    AnalyticTerrain shape;
    double spacing;  // grid, metres
    Camera cam;
};

Camera camera(glm::dvec3 eye, double azimuth, double altitude, const AnalyticTerrain& s, double top) {
    Camera c;
    c.eye = eye, c.azimuth = azimuth, c.altitude = altitude, c.fov = 40.0;
    c.width = 400, c.height = 300;
    fit_depth_range(c, {-s.half_extent, -s.half_extent, 0.0}, {s.half_extent, s.half_extent, top});
    return c;
}

Case two_hills_case() {
    AnalyticTerrain s;
    s.shape = AnalyticShape::two_hills, s.height = 250.0, s.width = 150.0, s.half_extent = 3000.0;
    return {"two hills", s, 25.0, camera({0.0, -1300.0, 700.0}, 0.0, -14.0, s, 400.0)};
}

Case cliff_case() {
    AnalyticTerrain s;
    s.shape = AnalyticShape::smooth_cliff, s.height = 100.0, s.width = 15.0, s.half_extent = 1000.0;
    return {"smooth cliff", s, 5.0, camera({-150.0, -600.0, 260.0}, 15.0, -15.0, s, 100.0)};
}

Case saddle_case() {
    AnalyticTerrain s;
    s.shape = AnalyticShape::saddle, s.height = 250.0, s.width = 150.0, s.half_extent = 3000.0;
    return {"saddle", s, 25.0, camera({0.0, -1300.0, 520.0}, 0.0, -12.0, s, 250.0)};
}

struct Result {
    LineAccuracy mask, strokes;
};

Result run(const Case& c) {
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    TerrainRenderer renderer(test::test_context().gl(), mesh, c.cam.width, c.cam.height);
    const FrameImages img = renderer.render(c.cam, {});
    const std::vector<ImagePolyline> ref = analytic_silhouettes(c.shape, c.cam, false);
    const PixelMask drawn = rasterize_strokes(traced_silhouettes(img), c.cam.width, c.cam.height);
    if (const char* dir = std::getenv("PENINK_DEBUG_PGM")) {  // mask grey, strokes black, reference white
        const PixelMask r = rasterize_polylines(ref, c.cam.width, c.cam.height);
        FILE* f = std::fopen((std::string(dir) + "/" + c.name + ".pgm").c_str(), "wb");
        std::fprintf(f, "P5 %d %d 255\n", c.cam.width, c.cam.height);
        for (std::size_t i = 0; i < img.toward.depth.size(); ++i)
            std::fputc(r.on[i] ? 255 : drawn.on[i] ? 0 : img.silhouettes.on[i] ? 90 : 180, f);
        std::fclose(f);
    }
    Result out{line_accuracy(img.silhouettes, ref, {1.0, 1.5}), line_accuracy(drawn, ref, {1.0, 1.5})};
    for (const auto& [what, a] : {std::pair{"mask", &out.mask}, std::pair{"strokes", &out.strokes}})
        std::printf("%-12s %-7s P1 %.3f R1 %.3f P1.5 %.3f R1.5 %.3f  d->r %.2f r->d %.2f px  ref %.0f px\n", c.name, what,
                    a->at(1.0).precision, a->at(1.0).recall, a->at(1.5).precision, a->at(1.5).recall,
                    a->mean_drawn_to_reference, a->mean_reference_to_drawn, a->reference_length);
    return out;
}

void expect_accurate(const Case& c, double min_reference_px) {
    const Result r = run(c);
    EXPECT_GT(r.strokes.reference_length, min_reference_px);  // the view shows a long silhouette
    EXPECT_GE(r.strokes.at(1.5).precision, 0.95);
    EXPECT_GE(r.strokes.at(1.5).recall, 0.95);
    EXPECT_GE(r.mask.at(1.5).precision, 0.95);
    EXPECT_GE(r.mask.at(1.5).recall, 0.95);
}

}  // namespace

TEST(TowardAwayAccuracy, TwoHillsOneBehindTheOther) { expect_accurate(two_hills_case(), 300.0); }

TEST(TowardAwayAccuracy, SmoothCliffFromItsHighSide) { expect_accurate(cliff_case(), 350.0); }

TEST(TowardAwayAccuracy, SaddleBetweenTwoPeaks) { expect_accurate(saddle_case(), 300.0); }
