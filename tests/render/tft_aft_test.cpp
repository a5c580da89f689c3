// TFT/AFT: eye distances of a flat plane seen straight down match the closed form, toward-facing
// fragments cover it and no away-facing ones exist; combined and separate modes agree.
#include <cmath>

#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "support/synthetic_terrain.hpp"
#include "render/terrain_renderer.hpp"

using namespace penink;

namespace {

Camera down_camera(double height) {
    Camera cam;
    cam.eye = {0.0, 0.0, height};
    cam.azimuth = 0.0, cam.altitude = -90.0, cam.fov = 60.0;
    cam.width = 64, cam.height = 48;
    cam.near_plane = 1.0, cam.far_plane = 10000.0;
    return cam;
}

}  // namespace

TEST(TftAft, FlatPlaneDistancesMatchClosedForm) {
    GlContext& ctx = test::test_context();
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(41, 41, 50.0, [](double, double) { return 0.0; }));
    const Camera cam = down_camera(500.0);
    TerrainRenderer renderer(ctx.gl(), mesh, cam.width, cam.height);
    const FrameImages img = renderer.render(cam, {});
    // Pixel centre (x+0.5, y+0.5) -> ray; distance to z=0 is H / cos(angle to the nadir).
    const double tan_half = std::tan(30.0 * M_PI / 180.0);
    double max_err = 0.0;
    for (int y = 0; y < cam.height; ++y) {
        for (int x = 0; x < cam.width; ++x) {
            const double sx = ((x + 0.5) / cam.width * 2.0 - 1.0) * tan_half;
            const double sy = ((y + 0.5) / cam.height * 2.0 - 1.0) * tan_half * cam.height / cam.width;
            const double expected = 500.0 * std::sqrt(1.0 + sx * sx + sy * sy);
            const float t = img.toward.depth[std::size_t(y) * cam.width + x];
            ASSERT_TRUE(std::isfinite(t)) << x << "," << y;
            EXPECT_FALSE(std::isfinite(img.away.depth[std::size_t(y) * cam.width + x]));
            max_err = std::max(max_err, std::abs(t - expected));
        }
    }
    EXPECT_LT(max_err, 0.05);  // float interpolation of a linear quantity over ~1000 m
    std::size_t sil = 0;
    for (auto v : img.silhouettes.on) sil += v != 0;
    EXPECT_EQ(sil, 0u);
}

TEST(TftAft, SeparatePassesAgreeWithCombined) {
    GlContext& ctx = test::test_context();
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(61, 61, 20.0, gaussian_hill(300.0, 150.0)));
    Camera cam = down_camera(2000.0);
    cam.eye = {0.0, -1500.0, 200.0};
    cam.altitude = -5.0;
    cam.width = 160, cam.height = 120;
    TerrainRenderer renderer(ctx.gl(), mesh, cam.width, cam.height);
    FrameOptions combined, separate;
    separate.separate_passes = true;
    const FrameImages a = renderer.render(cam, combined);
    const FrameImages b = renderer.render(cam, separate);
    std::size_t away = 0;
    for (std::size_t i = 0; i < a.toward.depth.size(); ++i) {
        const float ta = a.toward.depth[i], tb = b.toward.depth[i];
        EXPECT_EQ(std::isfinite(ta), std::isfinite(tb)) << i;
        if (std::isfinite(ta) && std::isfinite(tb)) {
            EXPECT_NEAR(ta, tb, 1e-3 * ta) << i;
        }
        away += std::isfinite(a.away.depth[i]);
    }
    EXPECT_GT(away, 50u);  // the far side of the hill faces away
    EXPECT_EQ(a.silhouettes.on, b.silhouettes.on);
}
