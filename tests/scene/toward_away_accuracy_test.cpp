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

AnalyticCase named(const char* name) { return *analytic_case(name, 400, 300); }

struct Result {
    LineAccuracy mask, strokes;
};

Result run(const AnalyticCase& c) {
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    TerrainRenderer renderer(test::test_context().gl(), mesh, c.camera.width, c.camera.height);
    const FrameImages img = renderer.render(c.camera, {});
    const std::vector<ImagePolyline> ref = analytic_silhouettes(c.shape, c.camera, false);
    const PixelMask drawn = rasterize_strokes(traced_silhouettes(img), c.camera.width, c.camera.height);
    if (const char* dir = std::getenv("PENINK_DEBUG_PGM")) {  // mask grey, strokes black, reference white
        const PixelMask r = rasterize_polylines(ref, c.camera.width, c.camera.height);
        FILE* f = std::fopen((std::string(dir) + "/" + c.name + ".pgm").c_str(), "wb");
        std::fprintf(f, "P5 %d %d 255\n", c.camera.width, c.camera.height);
        for (std::size_t i = 0; i < img.toward.depth.size(); ++i)
            std::fputc(r.on[i] ? 255 : drawn.on[i] ? 0 : img.silhouettes.on[i] ? 90 : 180, f);
        std::fclose(f);
    }
    Result out{line_accuracy(img.silhouettes, ref, {1.0, 1.5}), line_accuracy(drawn, ref, {1.0, 1.5})};
    for (const auto& [what, a] : {std::pair{"mask", &out.mask}, std::pair{"strokes", &out.strokes}})
        std::printf("%-13s %-7s P1 %.3f R1 %.3f P1.5 %.3f R1.5 %.3f  d->r %.2f r->d %.2f px  ref %.0f px\n", c.name.c_str(), what,
                    a->at(1.0).precision, a->at(1.0).recall, a->at(1.5).precision, a->at(1.5).recall,
                    a->mean_drawn_to_reference, a->mean_reference_to_drawn, a->reference_length);
    return out;
}

void expect_accurate(const AnalyticCase& c, double min_reference_px) {
    const Result r = run(c);
    EXPECT_GT(r.strokes.reference_length, min_reference_px);  // the view shows a long silhouette
    EXPECT_GE(r.strokes.at(1.5).precision, 0.95);
    EXPECT_GE(r.strokes.at(1.5).recall, 0.95);
    EXPECT_GE(r.mask.at(1.5).precision, 0.95);
    EXPECT_GE(r.mask.at(1.5).recall, 0.95);
}

}  // namespace

TEST(TowardAwayAccuracy, TwoHillsOneBehindTheOther) { expect_accurate(named("two-hills"), 300.0); }

TEST(TowardAwayAccuracy, SmoothCliffFromItsHighSide) { expect_accurate(named("smooth-cliff"), 350.0); }

TEST(TowardAwayAccuracy, SaddleBetweenTwoPeaks) { expect_accurate(named("saddle"), 300.0); }
