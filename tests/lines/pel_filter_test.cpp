// Xie et al., "Photic Extremum Lines" post-processing on a sphere whose normals carry noise: the
// Gaussian normal filter (surface/mesh_normals.hpp) and the line-strength threshold
// (strong_pel_lines) bring the noisy sphere's PELs back towards the clean sphere's, the terminator
// great circle p . l = 0 of a directional light (pel_sphere_test.cpp derives it). Measured as in
// pel_sphere_test: mean angular distance (radians) of the PEL end points from the terminator and
// the drawn length (clean: 2 pi r).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "lines/photic_extremum_lines.hpp"
#include "support/test_meshes.hpp"
#include "surface/mesh_normals.hpp"

using namespace penink;

namespace {

struct PelMeasure {
    double error = 0.0, length = 0.0;  // radians off the terminator; mesh units
};

PelMeasure measure(const std::vector<ObjectSegment>& segs, glm::vec3 l) {
    PelMeasure m;
    for (const auto& s : segs) {
        m.error += std::abs(glm::dot(s.a, l)) + std::abs(glm::dot(s.b, l));  // r = 1
        m.length += glm::length(s.b - s.a);
    }
    m.error = segs.empty() ? 1e9 : m.error / (2.0 * segs.size());
    return m;
}

struct Sphere {
    TriangleMesh mesh = test::icosphere(5, 1.0f);  // 20480 triangles, edges ~0.03
    PelGeometry geom = pel_geometry(mesh);
    glm::vec3 light = glm::normalize(glm::vec3(1.0f, 0.5f, 2.0f));
    float edge = mean_edge_length(mesh);

    std::vector<ObjectSegment> pels(const std::vector<glm::vec3>& normals) const {
        PelOptions o;
        o.light_at_eye = false, o.light_dir = light, o.clamp_diffuse = false, o.threshold = 0.3f;
        return photic_extremum_lines(mesh, geom, normals, {}, o).segments;
    }
};

}  // namespace

TEST(PelFilter, MeanEdgeLengthOfTheIcosphere) {
    const Sphere s;
    // Level-5 icosphere of radius 1: 2 * 10 * 4^5 + ... edges of chord ~ 1.1 / 2^5 (icosahedron edge
    // 1.05 at r = 1, halved 5 times, then pushed out onto the sphere: a little longer).
    EXPECT_GT(s.edge, 1.05f / 32.0f);
    EXPECT_LT(s.edge, 1.25f / 32.0f);
}

// Measured (noise 0.002; error rad, length): clean 0.0005, 6.28; noisy 0.225, 41.6; filtered with
// sigma = 0.75, 1, 1.5, 2.5 edges: 0.136, 22.4; 0.090, 13.6; 0.041, 8.0; 0.011, 6.35, the clean
// sphere unchanged by each. A plain Gaussian mean (no first-moment correction) gave the clean sphere
// itself 0.16-0.20, 15-25, and Laplacian smoothing (1-10 passes) 0.06-0.20: both tilt normals.
TEST(PelFilter, GaussianNormalFilterBringsNoisyPelsBackToTheTerminator) {
    const Sphere s;
    const auto clean_n = test::radial_normals(s.mesh), noisy_n = test::noisy_normals(clean_n, 0.002f, 42);
    const PelMeasure clean = measure(s.pels(clean_n), s.light);
    const PelMeasure raw = measure(s.pels(noisy_n), s.light);
    const PelMeasure filtered = measure(s.pels(gaussian_filter_normals(s.mesh, noisy_n, 1.5f * s.edge)), s.light);
    // The filter leaves the clean sphere's PEL where it was: a Gaussian mean of radial normals over
    // a symmetric patch is radial.
    const PelMeasure clean_filtered =
        measure(s.pels(gaussian_filter_normals(s.mesh, clean_n, 1.5f * s.edge)), s.light);
    RecordProperty("noisy_error_length", std::to_string(raw.error) + " " + std::to_string(raw.length));
    RecordProperty("filtered_error_length", std::to_string(filtered.error) + " " + std::to_string(filtered.length));
    EXPECT_LT(clean.error, 0.002);
    EXPECT_GT(raw.error, 0.1);
    EXPECT_LT(filtered.error, 0.25 * raw.error);
    EXPECT_LT(std::abs(filtered.length - clean.length), 0.25 * std::abs(raw.length - clean.length));
    EXPECT_LT(clean_filtered.error, 0.002);
    EXPECT_NEAR(clean_filtered.length, clean.length, 0.02 * clean.length);
}

TEST(PelFilter, FilterWidthZeroReturnsTheNormals) {
    const Sphere s;
    const auto n = test::noisy_normals(test::radial_normals(s.mesh), 0.002f, 7);
    EXPECT_EQ(gaussian_filter_normals(s.mesh, n, 0.0f), n);
}

TEST(PelFilter, LineStrengthDropsShortNoisyLinesAndKeepsTheGreatCircle) {
    const Sphere s;
    const auto clean_n = test::radial_normals(s.mesh);
    const auto clean = s.pels(clean_n);
    // The clean terminator is one line of strength ~ 2 pi (g ~ 1 along a circle of length 2 pi):
    const std::vector<float> st = pel_line_strengths(clean);
    ASSERT_FALSE(st.empty());
    EXPECT_NEAR(st.front(), 2.0 * M_PI, 0.1 * 2.0 * M_PI);
    EXPECT_EQ(strong_pel_lines(clean, 20.0f * s.edge).size(), clean.size());
    EXPECT_TRUE(strong_pel_lines(clean, 7.0f).empty());  // above the circle's strength

    const auto raw = s.pels(test::noisy_normals(clean_n, 0.001f, 42));
    // Measured: error 0.134 -> 0.038, length 25.4 -> 3.2 (1551 -> 184 segments): the noise's loops
    // go, and with them the pieces the noise broke off the terminator.
    const auto kept = strong_pel_lines(raw, 20.0f * s.edge);
    const PelMeasure before = measure(raw, s.light), after = measure(kept, s.light);
    RecordProperty("before_error_length", std::to_string(before.error) + " " + std::to_string(before.length));
    RecordProperty("after_error_length", std::to_string(after.error) + " " + std::to_string(after.length));
    EXPECT_LT(after.error, 0.5 * before.error);
    EXPECT_LT(std::abs(after.length - 2.0 * M_PI), 0.5 * std::abs(before.length - 2.0 * M_PI));
}

