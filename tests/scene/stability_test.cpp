// Stability cases, each with an asserted outcome, for the three silhouette
// methods where it applies: flat terrain, nodata holes, grazing view, a camera very far and very
// close, a DEM larger than the view (only the visible window is modelled) and PN-patch cracks.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "input/analytic_terrain.hpp"
#include "support/synthetic_terrain.hpp"
#include "input/terrain_window.hpp"
#include "lines/line_accuracy.hpp"
#include "render/terrain_renderer.hpp"
#include "scene/terrain_frames.hpp"

using namespace penink;

namespace {

constexpr SilhouetteMethod all_methods[] = {SilhouetteMethod::toward_away, SilhouetteMethod::adjacency,
                                            SilhouetteMethod::edge_walk, SilhouetteMethod::object_space};

Camera camera(glm::dvec3 eye, double azimuth, double altitude, int w = 200, int h = 150) {
    Camera c;
    c.eye = eye, c.azimuth = azimuth, c.altitude = altitude, c.fov = 50.0, c.width = w, c.height = h;
    return c;
}

std::size_t count(const PixelMask& m) {
    std::size_t n = 0;
    for (auto v : m.on) n += v != 0;
    return n;
}

std::size_t covered(const FrameImages& img) {
    std::size_t n = 0;
    for (float d : img.toward.depth) n += std::isfinite(d);
    return n;
}

FrameImages render(const Terrain& t, const Camera& cam, SilhouetteMethod m, TessellationOptions tess = {}) {
    const SurfaceMesh mesh = mesh_from_terrain(t);
    TerrainRenderer r(test::test_context().gl(), mesh, cam.width, cam.height);
    FrameOptions o;
    o.silhouette_method = m, o.tessellation = tess;
    FrameImages img = r.render(cam, o);
    if (m == SilhouetteMethod::object_space) img.silhouettes = object_space_silhouette_mask(mesh, cam, tess);
    return img;
}

AnalyticTerrain shape(AnalyticShape s, double half_extent = 1000.0) {
    AnalyticTerrain a;
    a.shape = s, a.half_extent = half_extent;
    return a;
}

}  // namespace

TEST(Stability, FlatTerrainHasNoSilhouettes) {
    const Terrain t = analytic_grid(shape(AnalyticShape::plain), 50.0);
    Camera cam = camera({0.0, -1200.0, 150.0}, 0.0, -8.0);
    fit_depth_range(cam, {-1000, -1000, 0}, {1000, 1000, 1});
    for (SilhouetteMethod m : all_methods) {
        const FrameImages img = render(t, cam, m);
        EXPECT_EQ(count(img.silhouettes), 0u) << int(m);
        EXPECT_GT(covered(img), 5000u);
    }
}

TEST(Stability, NodataHoleRimIsNotASilhouette) {
    // A hole in a plain is bounded by mesh border edges, not by a contour: no silhouette pixels
    // (the rim is drawn by the surface-mask outline), and the hole stays uncovered.
    Terrain t = analytic_grid(shape(AnalyticShape::plain), 25.0);
    cut_hole(t, 0.0, 0.0, 200.0);
    Camera cam = camera({0.0, -900.0, 300.0}, 0.0, -18.0);
    fit_depth_range(cam, {-1000, -1000, 0}, {1000, 1000, 1});
    for (SilhouetteMethod m : all_methods) {
        const FrameImages img = render(t, cam, m);
        EXPECT_EQ(count(img.silhouettes), 0u) << int(m);
        glm::dvec2 centre;
        double depth;
        ASSERT_TRUE(project_to_pixel(cam, {0, 0, 0}, centre, depth));
        EXPECT_FALSE(std::isfinite(img.toward.depth[std::size_t(centre.y) * cam.width + std::size_t(centre.x)]));
    }
}

TEST(Stability, GrazingViewAtAltitudeZero) {
    const AnalyticTerrain hill = shape(AnalyticShape::gaussian_hill, 2000.0);
    Camera cam = camera({0.0, -1300.0, 200.0}, 0.0, 0.0, 400, 300);
    fit_depth_range(cam, {-2000, -2000, 0}, {2000, 2000, 250});
    const FrameImages img = render(analytic_grid(hill, 25.0), cam, SilhouetteMethod::toward_away);
    const LineAccuracy a = line_accuracy(img.silhouettes, analytic_silhouettes(hill, cam, true), {1.5, 2.0});
    std::printf("altitude 0: reference %.1f px, recall %.3f / %.3f, precision %.3f / %.3f at 1.5 / 2 px\n",
                a.reference_length, a.at(1.5).recall, a.at(2.0).recall, a.at(1.5).precision, a.at(2.0).precision);
    EXPECT_GT(a.reference_length, 100.0);
    EXPECT_GE(a.at(1.5).recall, 0.95);
}

TEST(Stability, CameraFarAwayLeavesAFewPixels) {
    const AnalyticTerrain hill = shape(AnalyticShape::gaussian_hill, 2000.0);
    Camera cam = camera({0.0, -150000.0, 40000.0}, 0.0, -std::atan2(40000.0, 150000.0) * 180.0 / M_PI);
    fit_depth_range(cam, {-2000, -2000, 0}, {2000, 2000, 250});
    for (SilhouetteMethod m : all_methods) {
        const FrameImages img = render(analytic_grid(hill, 25.0), cam, m);
        EXPECT_GT(covered(img), 0u) << int(m);
        EXPECT_LT(covered(img), 60u) << int(m);  // the 4 km DEM is a few pixels wide
        EXPECT_LE(count(img.silhouettes), 10u) << int(m);
    }
}

TEST(Stability, CameraJustAboveTheSurface) {
    const AnalyticTerrain hill = shape(AnalyticShape::gaussian_hill, 2000.0);
    const double y = -300.0, z = analytic_height(hill)(0.0, y) + 2.0;  // 2 m above the flank
    Camera cam = camera({0.0, y, z}, 0.0, 5.0);
    fit_depth_range(cam, {-2000, -2000, 0}, {2000, 2000, 250});
    for (SilhouetteMethod m : all_methods) {
        const FrameImages img = render(analytic_grid(hill, 25.0), cam, m);
        std::size_t nan = 0;
        for (float d : img.toward.depth) nan += std::isnan(d);
        EXPECT_EQ(nan, 0u);
        EXPECT_GT(covered(img), 1000u) << int(m);  // the slope ahead fills the lower image
    }
}

TEST(Stability, DemLargerThanTheViewIsCropped) {
    const AnalyticTerrain hill = shape(AnalyticShape::gaussian_hill, 2000.0);
    const Terrain full = analytic_grid(hill, 10.0);  // 401 x 401 nodes
    Camera cam = camera({0.0, -600.0, 500.0}, 0.0, -35.0);
    fit_depth_range(cam, {-2000, -2000, 0}, {2000, 2000, 250});
    const GridWindow w = visible_window(full, view_projection(cam), 1);
    const Terrain crop = crop_terrain(full, w);
    const std::size_t cells = std::size_t(crop.cols - 1) * (crop.rows - 1);
    std::printf("cropped to %dx%d nodes, %zu cells of %d\n", crop.cols, crop.rows, cells, 400 * 400);
    EXPECT_EQ(full.cols, 401);
    EXPECT_LT(cells, 400u * 400u / 3);  // measured: the view needs a third or less of the grid
    EXPECT_GT(cells, 1000u);
    const FrameImages a = render(full, cam, SilhouetteMethod::toward_away);
    const FrameImages b = render(crop, cam, SilhouetteMethod::toward_away);
    EXPECT_EQ(covered(a), covered(b));  // cropping changes nothing visible
    EXPECT_EQ(count(a.silhouettes), count(b.silhouettes));
}

TEST(Stability, NoCracksBetweenPnPatchesAtHighTessellation) {
    // Looking straight down on a hill whose grid fills the view: every pixel must be covered;
    // a crack between patches of different levels would leave background pixels.
    const AnalyticTerrain hill = shape(AnalyticShape::gaussian_hill, 1000.0);
    Camera cam = camera({0.0, 0.0, 1200.0}, 0.0, -90.0);
    fit_depth_range(cam, {-1000, -1000, 0}, {1000, 1000, 250});
    for (float target : {1.0f, 3.0f}) {
        TessellationOptions tess;
        tess.target_edge_px = target, tess.max_level = 16;
        const FrameImages img = render(analytic_grid(hill, 50.0), cam, SilhouetteMethod::toward_away, tess);
        EXPECT_EQ(covered(img), std::size_t(cam.width) * cam.height) << target;
    }
}
