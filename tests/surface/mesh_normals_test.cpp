// Vertex normals (area / angle weighting) and Laplacian normal smoothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "surface/mesh_normals.hpp"

using namespace penink;

namespace {

// Corner of a box: at the origin, one large triangle on z = 0 (area 8) and one small on x = 0
// (area 0.5), both with a right angle at the origin.
TriangleMesh corner() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {0, 4, 3}};
    m.material = {0, 0};
    m.material_names = {"default"};
    return m;
}

// Height field z = 0 on an n x n grid with unit spacing, CCW from above.
TriangleMesh flat_grid(int n) {
    TriangleMesh m;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) m.positions.emplace_back(i, j, 0);
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            unsigned a = j * n + i;
            m.triangles.emplace_back(a, a + 1, a + n + 1);
            m.triangles.emplace_back(a, a + n + 1, a + n);
        }
    m.material.assign(m.triangles.size(), 0);
    m.material_names = {"default"};
    return m;
}

double mean_angle_to_z(const std::vector<glm::vec3>& n) {
    double s = 0;
    for (const auto& v : n) s += std::acos(std::clamp(double(v.z), -1.0, 1.0));
    return s / double(n.size());
}

}  // namespace

TEST(MeshNormals, AreaAndAngleWeighting) {
    TriangleMesh m = corner();
    auto f = mesh_face_normals(m);
    EXPECT_EQ(f[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(f[1], glm::vec3(-1, 0, 0));
    // Area: (0,0,8) + (-0.5,0,0) normalised. Angle: both corners 90 degrees -> equal weights.
    auto area = mesh_vertex_normals(m, NormalWeighting::area);
    glm::vec3 expect_area = glm::normalize(glm::vec3(-0.5f, 0, 8));
    EXPECT_NEAR(glm::length(area[0] - expect_area), 0.0f, 1e-6f);
    auto angle = mesh_vertex_normals(m, NormalWeighting::angle);
    EXPECT_NEAR(glm::length(angle[0] - glm::normalize(glm::vec3(-1, 0, 1))), 0.0f, 1e-6f);
    // Vertex 1 only touches the first triangle.
    EXPECT_EQ(angle[1], glm::vec3(0, 0, 1));
}

TEST(MeshNormals, SmoothingReducesNormalNoise) {
    TriangleMesh m = flat_grid(30);
    auto n = mesh_vertex_normals(m);
    for (const auto& v : n) EXPECT_NEAR(v.z, 1.0f, 1e-6f);
    std::uint64_t s = 99;
    for (auto& v : n) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        float a = float((s >> 40) & 0xffff) / 65535.0f - 0.5f, b = float((s >> 20) & 0xffff) / 65535.0f - 0.5f;
        v = glm::normalize(v + 0.4f * glm::vec3(a, b, 0));
    }
    double e0 = mean_angle_to_z(n);
    double e1 = mean_angle_to_z(smooth_vertex_normals(m, n, 1));
    double e5 = mean_angle_to_z(smooth_vertex_normals(m, n, 5));
    EXPECT_GT(e0, 0.08);
    EXPECT_LT(e1, 0.7 * e0);
    EXPECT_LT(e5, 0.5 * e1);
    EXPECT_EQ(smooth_vertex_normals(m, n, 0), n);
    SurfaceMesh sm = surface_mesh_from(m, n);
    EXPECT_EQ(sm.pos.size(), m.positions.size());
    EXPECT_EQ(sm.face_normal.size(), m.triangles.size());
}
