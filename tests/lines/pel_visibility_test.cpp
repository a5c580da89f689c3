// Hidden-line removal of object-space lines against a CPU depth image of a sphere.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "lines/mesh_visibility.hpp"
#include "support/test_meshes.hpp"

using namespace penink;

namespace {

// Circle of radius rho in the plane y = y0, centred on the y axis.
ObjectPolyline circle_at_y(float y0, float rho) {
    ObjectPolyline pl;
    pl.kind = "pel";
    for (int k = 0; k <= 64; ++k) {
        double a = 2 * M_PI * k / 64;
        pl.points.emplace_back(rho * std::cos(a), y0, rho * std::sin(a));
    }
    return pl;
}

Camera looking_north(float dist) {
    Camera cam;
    cam.eye = {0.0, -dist, 0.0};
    cam.azimuth = 0.0;
    cam.altitude = 0.0;
    cam.fov = 40.0;
    cam.width = 200;
    cam.height = 150;
    cam.near_plane = 0.1;
    cam.far_plane = 100.0;
    return cam;
}

double image_length(const std::vector<Stroke>& strokes) {
    double len = 0;
    for (const auto& s : strokes)
        for (std::size_t i = 1; i < s.points.size(); ++i) len += glm::length(s.points[i] - s.points[i - 1]);
    return len;
}

}  // namespace

TEST(PelVisibility, DepthImageOfASphere) {
    TriangleMesh m = test::uv_sphere(64, 1.0f);
    Camera cam = looking_north(5.0f);
    DepthImage img = rasterize_depth(m, cam);
    ASSERT_EQ(img.width, 200);
    ASSERT_EQ(img.height, 150);
    EXPECT_NEAR(img.depth[75 * 200 + 100], 4.0f, 0.01f);  // nearest point of the sphere
    EXPECT_TRUE(std::isinf(img.depth[0 * 200 + 0]));
    EXPECT_TRUE(std::isinf(img.depth[149 * 200 + 199]));
    int covered = 0;
    for (float d : img.depth) covered += std::isfinite(d);
    // Projected disc: angular radius asin(1/5); focal length 100 / tan(20 deg) px.
    double f = 100.0 / std::tan(20.0 * M_PI / 180.0), rad = f * std::tan(std::asin(0.2));
    EXPECT_NEAR(covered, M_PI * rad * rad, 0.03 * M_PI * rad * rad);
}

TEST(PelVisibility, FrontCircleVisibleBackCircleHidden) {
    TriangleMesh m = test::uv_sphere(64, 1.0f);
    Camera cam = looking_north(5.0f);
    DepthImage img = rasterize_depth(m, cam);
    // Slightly outside the sphere so the faceted surface never covers the circle.
    auto front = visible_strokes({circle_at_y(-0.6f, 0.81f)}, img, cam);
    auto back = visible_strokes({circle_at_y(0.6f, 0.81f)}, img, cam);
    ASSERT_EQ(front.size(), 1u);
    EXPECT_EQ(front[0].kind, "pel");
    EXPECT_EQ(front[0].points.size(), front[0].depth.size());
    EXPECT_EQ(front[0].points.size(), 65u);  // vertices kept, no extra samples
    EXPECT_TRUE(back.empty());
    for (std::size_t i = 0; i < front[0].points.size(); ++i) {
        glm::dvec2 px;
        double d;
        ASSERT_TRUE(project_to_pixel(cam, glm::dvec3(circle_at_y(-0.6f, 0.81f).points[i]), px, d));
        EXPECT_NEAR(front[0].points[i].x, px.x, 1e-3);
        EXPECT_NEAR(front[0].depth[i], d, 1e-4);
    }
}

TEST(PelVisibility, LineBehindTheSphereIsSplitAtItsOutline) {
    TriangleMesh m = test::uv_sphere(64, 1.0f);
    Camera cam = looking_north(5.0f);
    DepthImage img = rasterize_depth(m, cam);
    // Horizontal line at y = 2 behind the sphere from x = -2.4 to 2.4, eye distance 7 along y. It is
    // hidden where its projection x / 7 falls inside the sphere's disc, |x / 7| < tan(asin(0.2)).
    ObjectPolyline pl;
    pl.kind = "crease";
    pl.points = {{-2.4f, 2.0f, 0.0f}, {2.4f, 2.0f, 0.0f}};  // inside the image (|x| < 7 tan 20)
    auto strokes = visible_strokes({pl}, img, cam);
    ASSERT_EQ(strokes.size(), 2u);
    DepthImage empty{200, 150, std::vector<float>(200 * 150, std::numeric_limits<float>::infinity())};
    auto whole = visible_strokes({pl}, empty, cam);
    ASSERT_EQ(whole.size(), 1u);
    double hidden_x = 7.0 * std::tan(std::asin(0.2));
    EXPECT_NEAR(image_length(strokes) / image_length(whole), 1.0 - hidden_x / 2.4, 0.02);
    EXPECT_EQ(strokes[0].points.front(), whole[0].points.front());
    EXPECT_EQ(strokes[1].points.back(), whole[0].points.back());
    EXPECT_EQ(strokes[0].kind, "crease");
}

TEST(PelVisibility, SilhouetteOfTheSphereStaysVisible) {
    TriangleMesh m = test::uv_sphere(96, 1.0f);
    Camera cam = looking_north(5.0f);
    DepthImage img = rasterize_depth(m, cam);
    std::vector<glm::vec3> n;
    for (const auto& p : m.positions) n.push_back(glm::normalize(p));
    glm::vec3 eye(cam.eye);
    auto sil = chain_segments(mesh_silhouettes(m, n, eye), "silhouette");
    VisibilityOptions everything;
    everything.rel_tolerance = 1e9f;
    double all = image_length(visible_strokes(sil, img, cam, everything));
    double vis = image_length(visible_strokes(sil, img, cam));
    double f = 100.0 / std::tan(20.0 * M_PI / 180.0), rad = f * std::tan(std::asin(0.2));
    EXPECT_NEAR(all, 2 * M_PI * rad, 0.02 * 2 * M_PI * rad);
    EXPECT_GT(vis, 0.97 * all);
}

TEST(PelVisibility, PixelVisibleIsPointVisibleOfTheProjectedPoint) {
    // The same answer for a point and its projection, across a sphere's front, back and outline
    // and outside the image: pixel_visible is point_visible's test after the projection.
    TriangleMesh m = test::uv_sphere(64, 1.0f);
    Camera cam = looking_north(5.0f);
    DepthImage img = rasterize_depth(m, cam);
    const PixelProjector project(cam);
    VisibilityOptions o;
    o.rel_tolerance = 0.002f, o.abs_tolerance = 0.01f;
    int visible = 0, hidden = 0;
    for (int i = 0; i <= 40; ++i)
        for (int j = 0; j <= 40; ++j) {
            const glm::vec3 p(-3.0f + 0.15f * float(i), -1.2f + 0.06f * float(j), 0.3f);
            glm::dvec2 px;
            double d;
            const bool a = point_visible(img, cam, project, p, o);
            const bool b = project(glm::dvec3(p), px, d) && pixel_visible(img, cam, px, d, o);
            EXPECT_EQ(a, b) << p.x << " " << p.y;
            (a ? visible : hidden) += 1;
        }
    EXPECT_GT(visible, 100);  // both answers occur: the grid spans the sphere's front and back
    EXPECT_GT(hidden, 100);
}
