// TerrainLocator: triangle and barycentric coordinates of points on a grid mesh (cells split
// along the NW-SE diagonal, surface_mesh.hpp) against the closed form of the cell frame; points
// off the mesh; PN position and normal at hits.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/synthetic_terrain.hpp"
#include "surface/pn_triangle.hpp"
#include "surface/surface_mesh.hpp"
#include "surface/terrain_locator.hpp"

using namespace penink;

namespace {

constexpr int cols = 7, rows = 5;
constexpr double spacing = 10.0;

// Node (c, r) of terrain_from_function: x = (c - (cols-1)/2) s, y = ((rows-1)/2 - r) s.
double node_x(double c) { return (c - (cols - 1) * 0.5) * spacing; }
double node_y(double r) { return ((rows - 1) * 0.5 - r) * spacing; }

double bumpy(double x, double y) { return 3.0 * std::sin(x * 0.07) + 2.0 * std::cos(y * 0.11) + 0.01 * x * y; }

// Expected weights of the cell's nodes a (NW), b (NE), s (SW), d (SE) at cell coordinates
// u (east) and v (south), both in [0, 1]: triangle {a, s, d} below the diagonal (v > u),
// {a, d, b} above it.
struct Expected {
    std::uint32_t triangle;
    glm::vec3 bary;
};

Expected expected_hit(int c, int r, double u, double v) {
    const std::uint32_t first = std::uint32_t(2 * (r * (cols - 1) + c));
    if (v > u) return {first, glm::vec3(float(1 - v), float(v - u), float(u))};
    return {first + 1, glm::vec3(float(1 - u), float(v), float(u - v))};
}

// Weight the hit gives to mesh vertex `vertex` (0 when the triangle does not use it).
float weight_of(const SurfaceMesh& m, const SurfaceHit& h, std::uint32_t vertex) {
    float w = 0.0f;
    for (int k = 0; k < 3; ++k)
        if (m.tri[h.triangle][k] == vertex) w += h.bary[k];
    return w;
}

}  // namespace

TEST(TerrainLocator, InteriorPointsGiveTriangleAndBarycentrics) {
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(cols, rows, spacing, bumpy));
    const TerrainLocator loc(mesh);
    const double uv[][2] = {{0.2, 0.7}, {0.7, 0.2}, {0.1, 0.9}, {0.9, 0.15}, {0.45, 0.5}, {0.55, 0.3}};
    int checked = 0;
    for (int r = 0; r + 1 < rows; ++r) {
        for (int c = 0; c + 1 < cols; ++c) {
            for (const auto& q : uv) {
                SurfaceHit hit;
                ASSERT_TRUE(loc.locate(node_x(c + q[0]), node_y(r + q[1]), hit));
                const Expected e = expected_hit(c, r, q[0], q[1]);
                EXPECT_EQ(hit.triangle, e.triangle) << c << "," << r << " uv " << q[0] << " " << q[1];
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(hit.bary[k], e.bary[k], 1e-5);
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 6 * 6 * 4);
}

TEST(TerrainLocator, NodesCellCentresAndDiagonalPoints) {
    const Terrain t = terrain_from_function(cols, rows, spacing, bumpy);
    const SurfaceMesh mesh = mesh_from_terrain(t);
    const TerrainLocator loc(mesh);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {  // a node: weight 1 on that vertex, whichever triangle
            SurfaceHit hit;
            ASSERT_TRUE(loc.locate(node_x(c), node_y(r), hit)) << c << "," << r;
            EXPECT_NEAR(weight_of(mesh, hit, std::uint32_t(t.index(c, r))), 1.0f, 1e-6) << c << "," << r;
        }
    }
    for (int r = 0; r + 1 < rows; ++r) {
        for (int c = 0; c + 1 < cols; ++c) {
            const std::uint32_t a = std::uint32_t(t.index(c, r)), d = std::uint32_t(t.index(c + 1, r + 1));
            for (double u : {0.5, 0.25, 0.8}) {  // on the NW-SE diagonal (u = v): only a and d weigh
                SurfaceHit hit;
                ASSERT_TRUE(loc.locate(node_x(c + u), node_y(r + u), hit));
                EXPECT_NEAR(weight_of(mesh, hit, a), 1.0 - u, 1e-5);
                EXPECT_NEAR(weight_of(mesh, hit, d), u, 1e-5);
                EXPECT_EQ(hit.triangle / 2, std::uint32_t(r * (cols - 1) + c));
            }
        }
    }
}

TEST(TerrainLocator, PointsOffTheMeshAreNotFound) {
    Terrain t = terrain_from_function(cols, rows, spacing, bumpy);
    t.valid[t.index(3, 2)] = 0;  // the six triangles around node (3, 2) disappear
    const SurfaceMesh mesh = mesh_from_terrain(t);
    ASSERT_EQ(mesh.tri.size(), std::size_t(2 * (cols - 1) * (rows - 1) - 6));
    const TerrainLocator loc(mesh);
    SurfaceHit hit;
    const double x0 = node_x(0), x1 = node_x(cols - 1), y0 = node_y(rows - 1), y1 = node_y(0);
    EXPECT_FALSE(loc.locate(x0 - 0.5, 0.0, hit));
    EXPECT_FALSE(loc.locate(x1 + 0.5, 0.0, hit));
    EXPECT_FALSE(loc.locate(0.0, y0 - 0.5, hit));
    EXPECT_FALSE(loc.locate(0.0, y1 + 0.5, hit));
    EXPECT_FALSE(loc.locate(1e6, -1e6, hit));
    EXPECT_FALSE(loc.locate(node_x(3) + 1.0, node_y(2) - 1.0, hit));  // inside the hole
    EXPECT_FALSE(loc.locate(node_x(3) - 2.0, node_y(2) + 3.0, hit));
    EXPECT_TRUE(loc.locate(x1, y1, hit));  // corners of the grid are on the mesh
    EXPECT_TRUE(loc.locate(x0, y0, hit));
    // Node (3, 2) is NW of cell (3, 2) (both halves gone) and NE of cell (2, 2) (its {a, d, b} half gone).
    EXPECT_FALSE(loc.locate(node_x(3.7), node_y(2.2), hit));
    EXPECT_FALSE(loc.locate(node_x(2.8), node_y(2.2), hit));
    ASSERT_TRUE(loc.locate(node_x(2.3), node_y(2.8), hit));  // cell (2, 2), SW half {a, s, d}, keeps all nodes
    EXPECT_NEAR(weight_of(mesh, hit, std::uint32_t(t.index(2, 2))), 0.2f, 1e-5);
    const SurfaceMesh empty;
    const TerrainLocator none(empty);
    EXPECT_FALSE(none.locate(0.0, 0.0, hit));
}

TEST(TerrainLocator, LargeGridEveryQueryInsideItsTriangle) {
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(181, 123, 7.5, gaussian_hill(200.0, 150.0)));
    const TerrainLocator loc(mesh);
    std::uint64_t s = 0x9e3779b97f4a7c15ull;
    int found = 0;
    for (int i = 0; i < 20000; ++i) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        const double fx = double(s >> 11) / double(1ull << 53);
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        const double fy = double(s >> 11) / double(1ull << 53);
        const double x = (fx - 0.5) * 180 * 7.5, y = (fy - 0.5) * 122 * 7.5;
        SurfaceHit hit;
        ASSERT_TRUE(loc.locate(x, y, hit)) << x << "," << y;
        const glm::uvec3 v = mesh.tri[hit.triangle];
        const glm::dvec2 p = glm::dvec2(mesh.pos[v.x]) * double(hit.bary.x) + glm::dvec2(mesh.pos[v.y]) * double(hit.bary.y) +
                             glm::dvec2(mesh.pos[v.z]) * double(hit.bary.z);
        EXPECT_NEAR(p.x, x, 1e-3);
        EXPECT_NEAR(p.y, y, 1e-3);
        EXPECT_GE(std::min({hit.bary.x, hit.bary.y, hit.bary.z}), -1e-6f);
        EXPECT_NEAR(hit.bary.x + hit.bary.y + hit.bary.z, 1.0f, 1e-5);
        ++found;
    }
    EXPECT_EQ(found, 20000);
}

TEST(TerrainLocator, PnPositionAndNormalMatchThePatch) {
    const Terrain t = terrain_from_function(cols, rows, spacing, bumpy);
    const SurfaceMesh mesh = mesh_from_terrain(t);
    const TerrainLocator loc(mesh);
    const int c = 2, r = 1;
    for (const auto& q : {glm::dvec2(0.3, 0.6), glm::dvec2(0.8, 0.1)}) {
        SurfaceHit hit;
        ASSERT_TRUE(loc.locate(node_x(c + q.x), node_y(r + q.y), hit));
        const Expected e = expected_hit(c, r, q.x, q.y);
        const glm::uvec3 v = mesh.tri[e.triangle];
        const PnPatch patch = pn_patch(mesh.pos[v.x], mesh.pos[v.y], mesh.pos[v.z], mesh.normal[v.x],
                                       mesh.normal[v.y], mesh.normal[v.z]);
        const glm::vec3 p = loc.pn_position_at(hit), want = pn_position(patch, e.bary);
        const glm::vec3 n = loc.pn_normal_at(hit), want_n = pn_normal(patch, e.bary);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(p[k], want[k], 1e-4);
            EXPECT_NEAR(n[k], want_n[k], 1e-5);
        }
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5);
    }
    // At a node the PN surface passes through the node with the vertex normal.
    SurfaceHit hit;
    ASSERT_TRUE(loc.locate(node_x(4), node_y(3), hit));
    const std::size_t i = t.index(4, 3);
    const glm::vec3 p = loc.pn_position_at(hit), n = loc.pn_normal_at(hit);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(p[k], mesh.pos[i][k], 1e-4);
        EXPECT_NEAR(n[k], mesh.normal[i][k], 1e-5);
    }
}

TEST(TerrainLocator, TiltedPlaneHasPlaneNormalAndHeight) {
    // z = 0.3 x - 0.2 y + 50: normal (-0.3, 0.2, 1) / |.|
    const SurfaceMesh mesh = mesh_from_terrain(
        terrain_from_function(cols, rows, spacing, [](double x, double y) { return 0.3 * x - 0.2 * y + 50.0; }));
    const TerrainLocator loc(mesh);
    const glm::dvec3 want = glm::normalize(glm::dvec3(-0.3, 0.2, 1.0));
    for (double x = -29.0; x <= 29.0; x += 3.7) {
        for (double y = -19.0; y <= 19.0; y += 2.9) {
            SurfaceHit hit;
            ASSERT_TRUE(loc.locate(x, y, hit));
            const glm::vec3 n = loc.pn_normal_at(hit), p = loc.pn_position_at(hit);
            EXPECT_NEAR(n.x, want.x, 1e-5);
            EXPECT_NEAR(n.y, want.y, 1e-5);
            EXPECT_NEAR(n.z, want.z, 1e-5);
            EXPECT_NEAR(p.x, x, 1e-4);  // flat patches: no PN displacement
            EXPECT_NEAR(p.y, y, 1e-4);
            EXPECT_NEAR(p.z, 0.3 * x - 0.2 * y + 50.0, 1e-4);
        }
    }
}
