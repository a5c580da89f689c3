// Loop subdivision through CGAL: counts after each iteration, smoothing toward the limit surface,
// and the errors for meshes it cannot subdivide.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "input/mesh_subdivision.hpp"

using namespace penink;

namespace {

TriangleMesh octahedron() {
    TriangleMesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    m.material.assign(8, 0);
    m.material_names = {"default"};
    m.source = "octahedron";
    return m;
}

}  // namespace

TEST(MeshSubdivision, CountsFollowLoopRule) {
    // Closed mesh: F' = 4F, V' = V + E, E = 3F/2. Octahedron: V 6, E 12, F 8.
    TriangleMesh m = octahedron();
    loop_subdivide(m, 1);
    EXPECT_EQ(m.triangles.size(), 32u);
    EXPECT_EQ(m.positions.size(), 18u);
    loop_subdivide(m, 1);
    EXPECT_EQ(m.triangles.size(), 128u);
    EXPECT_EQ(m.positions.size(), 18u + 48u);
    EXPECT_EQ(m.material.size(), 128u);
}

TEST(MeshSubdivision, SmoothsTowardASphereLikeSurface) {
    // The octahedron's vertices lie at r = 1 and its face centres at r = 0.577 (ratio 1.73). Loop
    // is approximating (the surface shrinks) and smooth: after 3 iterations the radii measured
    // here lie in [0.414, 0.438], a ratio of 1.06.
    TriangleMesh m = octahedron();
    loop_subdivide(m, 3);
    float lo = 10, hi = 0;
    for (const glm::vec3& p : m.positions) lo = std::min(lo, glm::length(p)), hi = std::max(hi, glm::length(p));
    EXPECT_GT(lo, 0.40f);
    EXPECT_LT(hi, 0.45f);
    EXPECT_LT(hi / lo, 1.1f);
    EXPECT_EQ(m.triangles.size(), 8u * 64u);
}

TEST(MeshSubdivision, ZeroIterationsLeavesTheMesh) {
    TriangleMesh m = octahedron();
    loop_subdivide(m, 0);
    EXPECT_EQ(m.triangles.size(), 8u);
}

TEST(MeshSubdivision, Errors) {
    TriangleMesh m = octahedron();
    m.material_names = {"a", "b"};
    try {
        loop_subdivide(m, 1);
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: input: octahedron: cannot subdivide a mesh with several materials");
    }
    TriangleMesh bad = octahedron();
    bad.triangles.push_back({0, 2, 4});  // the same oriented edge used twice: not a manifold
    try {
        loop_subdivide(bad, 1);
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: input: octahedron: cannot subdivide: the mesh is not an oriented manifold");
    }
}
