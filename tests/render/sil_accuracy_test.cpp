// Toward/Away silhouettes (Mower, "Fast Image-Space Silhouette Extraction", 3.2) against the closed form: a Gaussian hill seen at a
// grazing angle. The exact silhouette is the visible part of the contour generator
// n(p) . (eye - p) = 0 of the analytic surface, with farther terrain behind it. We require that
// >= 95 % of its projected length lies within 1.5 px of a detected silhouette pixel centre.
// Tolerance: the detector marks the pixel whose centre ray grazes the near side of the
// silhouette, so up to one pixel of offset is inherent; 1.5 px allows for that plus the PN
// approximation of the analytic surface by a 25 m grid (< 0.5 m, ~0.15 px here).
#include <cmath>

#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "support/synthetic_terrain.hpp"
#include "render/terrain_renderer.hpp"

using namespace penink;

namespace {

constexpr double hill_h = 250.0, sigma = 150.0, half_extent = 2000.0;

double height(double x, double y) { return hill_h * std::exp(-(x * x + y * y) / (2 * sigma * sigma)); }

glm::dvec3 normal_at(double x, double y) {
    const double k = -height(x, y) / (sigma * sigma);
    return glm::normalize(glm::dvec3(-k * x, -k * y, 1.0));
}

// True when the segment eye -> p (stopping just short of p) passes above the terrain.
bool visible(const glm::dvec3& eye, const glm::dvec3& p) {
    for (int i = 1; i < 4000; ++i) {
        const glm::dvec3 q = eye + (p - eye) * (i / 4000.0 * 0.995);
        if (q.z < height(q.x, q.y) - 0.01) return false;
    }
    return true;
}

// True when the ray from eye through p hits terrain beyond p inside the grid.
bool terrain_behind(const glm::dvec3& eye, const glm::dvec3& p) {
    const glm::dvec3 d = glm::normalize(p - eye);
    for (double s = 5.0; s < 8000.0; s += 5.0) {
        const glm::dvec3 q = p + d * s;
        if (std::abs(q.x) > half_extent || std::abs(q.y) > half_extent) return false;
        if (q.z < height(q.x, q.y)) return true;
    }
    return false;
}

struct RefPoint { glm::dvec2 px; bool ok; };

}  // namespace

TEST(SilAccuracy, GaussianHillAtGrazingView) {
    const Terrain terrain = terrain_from_function(161, 161, 25.0, height);
    const SurfaceMesh mesh = mesh_from_terrain(terrain);
    Camera cam;
    cam.eye = {0.0, -1300.0, 450.0};
    cam.azimuth = 0.0, cam.altitude = -10.0, cam.fov = 40.0;
    cam.width = 400, cam.height = 300;
    fit_depth_range(cam, {-half_extent, -half_extent, 0.0}, {half_extent, half_extent, hill_h});
    TerrainRenderer renderer(test::test_context().gl(), mesh, cam.width, cam.height);
    const FrameImages img = renderer.render(cam, {});
    if (std::getenv("PENINK_DEBUG_PGM")) {
        FILE* f = std::fopen("/tmp/sil.pgm", "wb");
        std::fprintf(f, "P5 %d %d 255\n", cam.width, cam.height);
        for (std::size_t i = 0; i < img.toward.depth.size(); ++i) {
            const float t = img.toward.depth[i];
            const unsigned char v = img.silhouettes.on[i] ? 0 : std::isfinite(t) ? (unsigned char)(100 + t / 40) : 255;
            std::fputc(v, f);
        }
        std::fclose(f);
    }

    // Reference: roots of n.(eye-p) along rays from the hill's axis, 7200 directions.
    const int n_theta = 7200;
    std::vector<RefPoint> ref(n_theta, {{0, 0}, false});
    for (int i = 0; i < n_theta; ++i) {
        const double th = 2 * M_PI * i / n_theta;
        auto g = [&](double r) {
            const double x = r * std::cos(th), y = r * std::sin(th);
            return glm::dot(normal_at(x, y), cam.eye - glm::dvec3(x, y, height(x, y)));
        };
        for (double r = 1.0; r < 4 * sigma; r += 1.0) {
            if ((g(r) > 0) == (g(r + 1.0) > 0)) continue;
            double a = r, b = r + 1.0;
            for (int k = 0; k < 40; ++k) ((g(a) > 0) == (g(0.5 * (a + b)) > 0) ? a : b) = 0.5 * (a + b);
            const glm::dvec3 p(a * std::cos(th), a * std::sin(th), height(a * std::cos(th), a * std::sin(th)));
            double depth = 0;
            if (visible(cam.eye, p) && terrain_behind(cam.eye, p) && project_to_pixel(cam, p, ref[i].px, depth))
                ref[i].ok = true;
            break;  // the generator is crossed once per ray on this hill
        }
    }
    auto near_detected = [&](glm::dvec2 q) {
        for (int y = int(q.y) - 2; y <= int(q.y) + 2; ++y)
            for (int x = int(q.x) - 2; x <= int(q.x) + 2; ++x) {
                if (x < 0 || y < 0 || x >= cam.width || y >= cam.height) continue;
                if (!img.silhouettes.on[std::size_t(y) * cam.width + x]) continue;
                if (glm::length(glm::dvec2(x + 0.5, y + 0.5) - q) <= 1.5) return true;
            }
        return false;
    };
    double total = 0, covered = 0;
    for (int i = 0; i < n_theta; ++i) {
        const RefPoint &a = ref[i], &b = ref[(i + 1) % n_theta];
        if (!a.ok || !b.ok) continue;
        const double len = glm::length(b.px - a.px);
        if (len > 5.0) continue;  // not the same branch
        total += len;
        if (near_detected((a.px + b.px) * 0.5)) covered += len;
    }
    ASSERT_GT(total, 100.0) << "the reference silhouette should be long on screen; covered " << covered;
    EXPECT_GE(covered / total, 0.95) << "covered " << covered << " of " << total << " px";
}
