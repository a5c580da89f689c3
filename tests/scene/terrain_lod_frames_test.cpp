// Level of detail in the terrain frames: on an analytic Gaussian hill sampled every 2 m
// (2001 x 2001 nodes, 8 M full-resolution triangles), a frame's mesh follows the image, not the
// DEM, and its silhouettes agree with the full-resolution ones and with the exact contour.
#include <chrono>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "lines/line_accuracy.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"
#include "support/gl_test_context.hpp"
#include "input/analytic_terrain.hpp"

namespace penink {
namespace {

AnalyticTerrain hill() {
    AnalyticTerrain s;  // 250 m high, sigma 150 m, on a 4 km square
    return s;
}

const Terrain& hill_grid() {  // built once: 4 M nodes
    static const Terrain t = analytic_grid(hill(), 2.0);
    return t;
}

Scene silhouettes_scene(float tolerance_px) {
    Scene s;
    s.lines.creases.enabled = s.lines.ridges.enabled = false;
    s.terrain.surface_tolerance_px = tolerance_px;
    return s;
}

// The grazing view of the silhouette accuracy tests, at 800 x 600.
Camera grazing_camera() {
    Camera c;
    c.eye = {0.0, -1300.0, 450.0}, c.azimuth = 0.0, c.altitude = -10.0, c.fov = 40.0;
    c.width = 800, c.height = 600;
    fit_depth_range(c, {-2000.0, -2000.0, 0.0}, {2000.0, 2000.0, 250.0});
    return c;
}

SceneDrawing draw(const Terrain& t, const Camera& cam, float tolerance_px) {
    const Scene scene = silhouettes_scene(tolerance_px);
    TerrainFrames frames(test::test_context(), std::nullopt, t, cam.width, cam.height, Log{});
    return frames.draw(cam, scene);
}

// Share of the set pixels of `a` within `radius` px of a set pixel of `b`.
double share_near(const PixelMask& a, const PixelMask& b, double radius) {
    const int r = int(std::ceil(radius));
    std::size_t set = 0, near = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!a.on[std::size_t(y) * a.width + x]) continue;
            ++set;
            bool found = false;
            for (int dy = -r; dy <= r && !found; ++dy)
                for (int dx = -r; dx <= r && !found; ++dx) {
                    const int u = x + dx, v = y + dy;
                    found = u >= 0 && v >= 0 && u < b.width && v < b.height && dx * dx + dy * dy <= radius * radius &&
                            b.on[std::size_t(v) * b.width + u];
                }
            near += found;
        }
    return set ? double(near) / double(set) : 0.0;
}

std::size_t set_pixels(const PixelMask& m) {
    std::size_t n = 0;
    for (auto v : m.on) n += v != 0;
    return n;
}

TEST(TerrainLodFrames, TrianglesFollowTheImageNotTheDem) {
    const Terrain& t = hill_grid();
    ASSERT_GE(t.cols, 2000);
    Scene scene = silhouettes_scene(1.0f);
    scene.view.camera.width = 1000, scene.view.camera.height = 750;
    const Camera cam = scene_camera(scene, t);  // the whole DEM from the south-west
    const SceneDrawing d = draw(t, cam, 1.0f);
    const std::size_t full = 2 * std::size_t(t.cols - 1) * (t.rows - 1);
    std::printf("2001^2 hill at 2 m, 1000x750: %zu triangles selected of %zu\n", d.triangles, full);
    // The frame's mesh is bounded by the image: at most one triangle per 4 pixels here (the hill
    // is smooth: measured 0.02 per pixel), 100x fewer than the DEM holds.
    EXPECT_GT(d.triangles, 1000u);
    EXPECT_LE(d.triangles, std::size_t(cam.width) * cam.height / 4);
    EXPECT_LT(d.triangles * 100, full);
    EXPECT_FALSE(d.drawing.layer(LayerKind::surface).fill.empty());
}

TEST(TerrainLodFrames, SilhouettesAgreeWithFullResolutionAndTheExactContour) {
    const Terrain& t = hill_grid();
    const Camera cam = grazing_camera();
    const auto t0 = std::chrono::steady_clock::now();
    const SceneDrawing full = draw(t, cam, 0.0f);
    const auto t1 = std::chrono::steady_clock::now();
    const SceneDrawing lod = draw(t, cam, 1.0f);
    const auto t2 = std::chrono::steady_clock::now();
    std::printf("grazing view: full resolution %zu triangles (%.0f ms), level of detail %zu (%.0f ms)\n",
                full.triangles, std::chrono::duration<double, std::milli>(t1 - t0).count(), lod.triangles,
                std::chrono::duration<double, std::milli>(t2 - t1).count());
    EXPECT_LT(lod.triangles * 10, full.triangles);
    ASSERT_GT(set_pixels(full.silhouette_mask), 300u);
    // Within 1.5 px of each other: the coarse mesh's skyline moves at most tolerance_px (1 px) plus
    // the half pixel of rasterising either mask.
    const double precision = share_near(lod.silhouette_mask, full.silhouette_mask, 1.5);
    const double recall = share_near(full.silhouette_mask, lod.silhouette_mask, 1.5);
    std::printf("level of detail against full resolution at 1.5 px: precision %.3f recall %.3f\n", precision, recall);
    EXPECT_GE(precision, 0.95);
    EXPECT_GE(recall, 0.95);
    // Against the exact contour generator (the part with terrain behind it), as the full-resolution
    // surface is held in SilhouetteMethods.GaussianHillAtGrazingView.
    const LineAccuracy a = line_accuracy(lod.silhouette_mask, analytic_silhouettes(hill(), cam, true), {1.5});
    std::printf("level of detail against the exact contour at 1.5 px: precision %.3f recall %.3f\n",
                a.at(1.5).precision, a.at(1.5).recall);
    EXPECT_GT(a.reference_length, 300.0);
    EXPECT_GE(a.at(1.5).precision, 0.9);
    EXPECT_GE(a.at(1.5).recall, 0.95);
}

}  // namespace
}  // namespace penink
