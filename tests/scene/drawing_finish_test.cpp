// Drawing finish on synthetic scenes with a known answer (the silhouettes layer after
// finish_drawing with the default style):
//  - a near ridge in front of a higher far ridge whose peaks show above it in places: the near
//    ridge's skyline is one path across the frame, each piece of the far skyline ends on it
//    (T-junctions), no closed loops, no doubled lines;
//  - a DEM's cut edge, which is both a traced skyline and an object-space outline a pixel apart:
//    one line, not two.
#include <cmath>

#include <gtest/gtest.h>

#include "core/log.hpp"
#include "input/dem_reader.hpp"
#include "scene/terrain_view.hpp"
#include "export/style.hpp"
#include "lines/finish_drawing.hpp"
#include "lines/line_metrics.hpp"
#include "lines/simplify.hpp"
#include "scene/scene_style.hpp"
#include "scene/terrain_frames.hpp"
#include "support/gl_test_context.hpp"
#include "support/synthetic_terrain.hpp"

using namespace penink;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The silhouettes layer of one finished frame.
std::vector<Stroke> silhouettes(const Terrain& t, const Camera& cam) {
    Scene scene;
    scene.lines.creases.enabled = scene.lines.ridges.enabled = false;
    TerrainFrames frames(test::test_context(), std::nullopt, t, cam.width, cam.height, Log{});
    SceneDrawing d = frames.draw(cam, scene);
    finish_drawing(d.drawing, finish_options(default_style(), 1, true));
    return d.drawing.layer(LayerKind::silhouettes).strokes;
}

// Smallest distance from p to a stroke's polyline.
float distance_to(glm::vec2 p, const Stroke& s) {
    float best = 1e30f;
    for (std::size_t i = 1; i < s.points.size(); ++i) best = std::min(best, point_segment_distance(p, s.points[i - 1], s.points[i]));
    return best;
}

Camera looking_north(double eye_y, double eye_z, double altitude, int width, int height) {  // fov 40
    Camera c;
    c.eye = {0.0, eye_y, eye_z}, c.azimuth = 0.0, c.altitude = altitude, c.fov = 40.0;
    c.width = width, c.height = height;
    fit_depth_range(c, {-3000.0, -3000.0, 0.0}, {3000.0, 3000.0, 600.0});
    return c;
}

}  // namespace

TEST(DrawingFinish, NearRidgeIsOnePathAndFarPeaksEndOnIt) {
    // A near ridge (150 m, along x at y = -500) and, 1.3 km behind it, a far one whose height
    // swings between 150 and 450 m every kilometre: seen from (0, -2000) at 100 m looking north,
    // its peaks rise above the near skyline and its saddles hide behind it.
    const Terrain t = terrain_from_function(501, 501, 12.0, [](double x, double y) {
        const double near = 150.0 * std::exp(-(y + 500.0) * (y + 500.0) / (2.0 * 150.0 * 150.0));
        const double far_h = 300.0 + 150.0 * std::cos(2.0 * kPi * x / 1000.0);
        const double far = far_h * std::exp(-(y - 800.0) * (y - 800.0) / (2.0 * 200.0 * 200.0));
        return std::max(near, far);
    });
    const Camera cam = looking_north(-2000.0, 100.0, 2.0, 800, 400);
    const std::vector<Stroke> sil = silhouettes(t, cam);
    ASSERT_GE(sil.size(), 3u);
    // the near ridge's skyline: the stroke spanning the frame
    std::size_t near = 0;
    auto span = [](const Stroke& s) {
        float lo = 1e30f, hi = -1e30f;
        for (const glm::vec2& p : s.points) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
        return hi - lo;
    };
    for (std::size_t i = 0; i < sil.size(); ++i)
        if (span(sil[i]) > span(sil[near])) near = i;
    EXPECT_GT(span(sil[near]), 0.95f * float(cam.width)) << "the near ridge is one path across the frame";
    std::size_t t_junctions = 0;
    for (std::size_t i = 0; i < sil.size(); ++i) {
        const Stroke& s = sil[i];
        EXPECT_FALSE(is_closed(s)) << "stroke " << i << " is a closed loop";
        if (i == near) continue;
        for (const glm::vec2& end : {s.points.front(), s.points.back()}) {
            const bool at_border = end.x < 2.0f || end.x > float(cam.width) - 2.0f;
            const bool on_near = distance_to(end, sil[near]) < 2.0f;
            EXPECT_TRUE(at_border || on_near) << "stroke " << i << " ends at (" << end.x << ", " << end.y
                                              << ") neither on the near ridge nor at the frame's edge";
            t_junctions += on_near;
        }
    }
    EXPECT_GE(t_junctions, 4u);  // the far peaks' skylines end on the near one
    const LineMetrics m = line_metrics(sil);
    EXPECT_EQ(m.small_loops, 0u);
    EXPECT_LT(m.doubled_share(), 0.01);
}

TEST(DrawingFinish, CutEdgeAndSkylineDrawOneLine) {
    // The bundled volcano framed whole: along its far, cut edges the DEM's outline (an
    // object-space stroke) and the traced skyline lie a pixel apart. Drawn once (without the
    // merge, 2 % of the silhouettes' length is doubled here; 5.9 % in the example scene).
    const Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    Scene scene;
    scene.view.camera.width = 1000, scene.view.camera.height = 750;
    const Camera cam = scene_camera(scene, t);
    const std::vector<Stroke> sil = silhouettes(t, cam);
    ASSERT_FALSE(sil.empty());
    const LineMetrics m = line_metrics(sil);
    EXPECT_GT(m.length, 1000.0);
    EXPECT_EQ(m.small_loops, 0u);
    EXPECT_LT(m.doubled_share(), 0.01) << "two lines drawn along one edge";
}
