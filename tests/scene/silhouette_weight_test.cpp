// Silhouettes weigh by the depth gap behind them (lines/stroke_weight.hpp) on a rendered analytic
// terrain (input/analytic_terrain.hpp, two_hills: a Gaussian hill and, behind it, one 1.6x as
// high): seen level from the south below both tops, the near hill's crest stands against the far
// hill's slope, the far hill's crest against the sky. Each silhouette point is classed by the
// rendered toward image 3 px above it (surface there, farther than the point: a slope behind;
// none: sky); the pipeline's weights must put the sky's points above the slope's.
#include <cmath>

#include <gtest/gtest.h>

#include "input/analytic_terrain.hpp"
#include "render/terrain_renderer.hpp"
#include "scene/terrain_frames.hpp"
#include "support/gl_test_context.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;

TEST(SilhouetteWeight, HillHeavierAgainstTheSkyThanAgainstASlopeBehind) {
    AnalyticTerrain s;
    s.shape = AnalyticShape::two_hills;  // 250 m, sigma 150 m at the origin; 400 m at (120, 600)
    s.half_extent = 1500.0;
    Camera cam;
    cam.eye = {0.0, -1400.0, 180.0}, cam.azimuth = 0.0, cam.altitude = 2.0, cam.fov = 50.0;
    cam.width = 400, cam.height = 300;
    fit_depth_range(cam, {-s.half_extent, -s.half_extent, 0.0}, {s.half_extent, s.half_extent, 400.0});
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(s, 20.0));
    TerrainRenderer renderer(test::test_context().gl(), mesh, cam.width, cam.height);
    const FrameImages images = renderer.render(cam, FrameOptions{});
    Drawing drawing;
    add_frame_lines(images, mesh, cam, drawing);
    double sky = 0.0, slope = 0.0;
    int n_sky = 0, n_slope = 0;
    for (const Stroke& st : drawing.layer(LayerKind::silhouettes).strokes) {
        ASSERT_EQ(st.weight.size(), st.points.size());
        for (std::size_t i = 0; i < st.points.size(); ++i) {
            const int x = int(std::floor(st.points[i].x)), y = int(std::floor(st.points[i].y)) - 3;
            if (x < 0 || y < 0 || x >= cam.width || y >= cam.height || x < 10 || x >= cam.width - 10) continue;
            const float above = images.toward.depth[std::size_t(y) * cam.width + x];
            if (!std::isfinite(above)) sky += st.weight[i], ++n_sky;
            else if (above > st.depth[i] + 100.0f) slope += st.weight[i], ++n_slope;
        }
    }
    std::printf("silhouette points: %d against the sky, %d against the far hill\n", n_sky, n_slope);
    ASSERT_GT(n_sky, 20);
    ASSERT_GT(n_slope, 10);
    sky /= n_sky, slope /= n_slope;
    std::printf("silhouette weight: against the sky %.3f (%d points), against the far hill %.3f (%d points)\n", sky,
                n_sky, slope, n_slope);
    // the sky weighs 1 (points within the 3 px running mean of a slope's points may dip); the far
    // hill lies ~40 % of the near crest's distance behind it: g / (g + 0.1) ~ 0.8
    EXPECT_GT(sky, 0.95);
    EXPECT_LT(slope, 0.9);
    EXPECT_GT(sky, slope + 0.1);
}
