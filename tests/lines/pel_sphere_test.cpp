// Photic extremum lines on a finely tessellated sphere against the closed form.
//
// Sphere of radius r, directional light l (unit), phi = n . l = cos(theta) with theta the angle
// between the surface point and l. On the sphere the surface gradient of cos(theta) has length
// |grad phi| = sin(theta) / r and points towards the light (decreasing theta), so with
// w = grad phi / |grad phi|:  D_w |grad phi| = -cos(theta) / r^2  and
// D_w^2 |grad phi| = -sin(theta) / r^3.  D_w vanishes at theta = 90 deg, where D_w^2 < 0: the
// photic extremum line is the great circle p . l = 0 (the terminator), where g = 1.
// With the light at a finite eye e (distance d from the centre), a point at angle a from the
// direction of e has n . (e - p) = d cos(a) - r and |e - p| = sqrt(d^2 + r^2 - 2 d r cos(a)), so
// phi(a) = max(0, (d cos(a) - r) / |e - p|), lit for cos(a) > r / d. By symmetry |grad phi| =
// |d phi / d a| / r depends on a only and the PEL is the circle a* where it is maximal; for
// d = 5 r, a* is NOT the lit cap's rim (cos a = 0.2) but cos a* ~ 0.38 (the 1 / |e - p| falloff
// moves it inwards). The test finds a* from the closed-form phi(a) by dense sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "lines/photic_extremum_lines.hpp"
#include "support/test_meshes.hpp"

using namespace penink;

namespace {

// Mean |p . l| / r over all PEL endpoints: angular distance (radians, small) from the terminator.
double mean_terminator_error(const PelResult& r, glm::vec3 l, float radius) {
    double sum = 0;
    for (const auto& s : r.segments)
        sum += std::abs(glm::dot(s.a, l)) / radius + std::abs(glm::dot(s.b, l)) / radius;
    return r.segments.empty() ? 1e9 : sum / (2.0 * r.segments.size());
}

// cos(a*) of the closed-form PEL circle for a point light at distance d from a sphere of radius r.
double closed_form_pel_cos(double r, double d) {
    auto phi = [&](double a) {
        return std::max(0.0, (d * std::cos(a) - r) / std::sqrt(d * d + r * r - 2 * d * r * std::cos(a)));
    };
    double best = 0, best_a = 0, h = 1e-5;
    for (double a = 0.001; a < M_PI / 2; a += 1e-4) {
        double g = std::abs(phi(a + h) - phi(a - h)) / (2 * h * r);
        if (g > best) best = g, best_a = a;
    }
    return std::cos(best_a);
}

double total_length(const std::vector<ObjectSegment>& segs) {
    double len = 0;
    for (const auto& s : segs) len += glm::length(s.b - s.a);
    return len;
}

PelOptions directional(glm::vec3 l, float tau) {
    PelOptions o;
    o.light_at_eye = false;
    o.light_dir = l;
    o.clamp_diffuse = false;
    o.threshold = tau;
    return o;
}

}  // namespace

TEST(PelSphere, DirectionalLightGivesTheTerminatorGreatCircle) {
    const float r = 2.0f;
    TriangleMesh m = test::icosphere(5, r);  // 20480 triangles
    glm::vec3 l = glm::normalize(glm::vec3(1.0f, 0.5f, 2.0f));
    PelResult res = photic_extremum_lines(m, pel_geometry(m), test::radial_normals(m), glm::vec3(0, 0, 10),
                                          directional(l, 0.5f));
    ASSERT_GT(res.segments.size(), 100u);
    for (const auto& s : res.segments) {
        EXPECT_LT(std::abs(glm::dot(s.a, l)) / r, 0.02f);  // within ~1.1 degrees
        EXPECT_LT(std::abs(glm::dot(s.b, l)) / r, 0.02f);
        EXPECT_GT(s.strength, 0.97f);  // g = sin(90 deg) = 1 on the terminator
    }
    // The whole great circle is found: length 2 pi r within 5 %.
    EXPECT_NEAR(total_length(res.segments), 2.0 * M_PI * r, 0.05 * 2.0 * M_PI * r);
    // Chained into few closed-ish polylines.
    auto lines = chain_segments(res.segments, "pel");
    EXPECT_LE(lines.size(), 3u);
}

TEST(PelSphere, LightAtTheEyeGivesTheClosedFormCircle) {
    const float r = 1.0f;
    TriangleMesh m = test::icosphere(5, r);
    glm::vec3 eye(0.0f, -4.0f, 3.0f);  // d = |e| = 5
    const double c_star = closed_form_pel_cos(r, 5.0);
    EXPECT_NEAR(c_star, 0.38, 0.02);  // the closed form itself (not the rim at 0.2)
    PelOptions o;  // defaults: light at the eye, clamped diffuse
    o.threshold = 0.5f;
    PelResult res = photic_extremum_lines(m, pel_geometry(m), test::radial_normals(m), eye, o);
    ASSERT_GT(res.segments.size(), 100u);
    double err = 0, worst = 0;
    for (const auto& s : res.segments) {
        double e = std::abs(glm::dot(s.a, eye) / (5.0 * r) - c_star);
        err += e;
        worst = std::max(worst, e);
    }
    EXPECT_LT(err / double(res.segments.size()), 0.01);  // mean |cos a - cos a*|
    EXPECT_LT(worst, 0.03);
    double circle = 2.0 * M_PI * r * std::sqrt(1.0 - c_star * c_star);
    EXPECT_NEAR(total_length(res.segments), circle, 0.05 * circle);
    // Silhouettes from the same eye: the circle n . (e - p) = 0, i.e. p . e = r^2.
    auto sil = mesh_silhouettes(m, test::radial_normals(m), eye);
    ASSERT_GT(sil.size(), 100u);
    for (const auto& s : sil) EXPECT_NEAR(glm::dot(s.a, eye), r * r, 0.01);
}

TEST(PelSphere, ThresholdAboveTheMaximumLeavesNothing) {
    TriangleMesh m = test::icosphere(4, 1.0f);
    glm::vec3 l = glm::normalize(glm::vec3(0.3f, -1.0f, 0.5f));
    auto geom = pel_geometry(m);
    auto n = test::radial_normals(m);
    PelResult all = photic_extremum_lines(m, geom, n, {}, directional(l, 0.0f));
    PelResult none = photic_extremum_lines(m, geom, n, {}, directional(l, 1.01f));
    EXPECT_GT(all.segments.size(), 50u);
    EXPECT_EQ(none.segments.size(), 0u);
    float gmax = 0;
    for (float g : all.field.g) gmax = std::max(gmax, g);
    EXPECT_FLOAT_EQ(gmax, 1.0f);
    EXPECT_NEAR(all.field.max_gradient, 1.0f, 0.01f);  // sin(90 deg) / r with r = 1
}

// PELs use third derivatives of the normals: with edges of ~0.03 r, normal noise of 0.001 already
// adds spurious maxima (the paper smooths normals first, see smooth_vertex_normals). Measured
// mean error (radians off the terminator) for amplitudes 0, 5e-4, 1e-3, 2e-3, 5e-3:
// 0.0005, 0.073, 0.13, 0.23, 0.37, and the drawn length grows 6.3, 16, 25, 42, 69.
TEST(PelSphere, NormalNoiseDegradesMonotonically) {
    const float r = 1.0f;
    TriangleMesh m = test::icosphere(5, r);
    glm::vec3 l = glm::normalize(glm::vec3(1.0f, 0.5f, 2.0f));
    auto geom = pel_geometry(m);
    const float amps[] = {0.0f, 0.0005f, 0.001f, 0.002f, 0.005f};
    std::vector<double> err, len;
    for (float amp : amps) {
        auto res = photic_extremum_lines(m, geom, test::noisy_normals(test::radial_normals(m), amp, 42), {},
                                         directional(l, 0.3f));
        err.push_back(mean_terminator_error(res, l, r));
        len.push_back(total_length(res.segments));
    }
    EXPECT_LT(err[0], 0.002);
    EXPECT_LT(err[1], 0.1);
    EXPECT_LT(err[4], 0.5);  // still biased towards the terminator (uniform would be 0.5)
    for (std::size_t i = 1; i < err.size(); ++i) {
        EXPECT_GT(err[i], err[i - 1]) << "amplitude " << amps[i];
        EXPECT_GT(len[i], len[i - 1]) << "amplitude " << amps[i];
    }
}
