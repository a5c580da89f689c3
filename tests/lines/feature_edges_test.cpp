// Feature edges and planar face groups on a cube (2 triangles per face), an open quad and a
// smooth sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "lines/feature_edges.hpp"
#include "support/test_meshes.hpp"

using namespace penink;

namespace {

std::map<EdgeKind, int> count_kinds(const std::vector<MeshEdge>& edges) {
    std::map<EdgeKind, int> c;
    for (const auto& e : edges) c[e.kind]++;
    return c;
}

}  // namespace

TEST(FeatureEdges, CubeHasExactlyItsTwelveEdges) {
    TriangleMesh m = test::unit_cube();
    auto all = classify_edges(m, {});
    EXPECT_EQ(all.size(), 18u);  // 12 cube edges + 6 face diagonals
    auto f = feature_edges(m, {});
    ASSERT_EQ(f.size(), 12u);
    for (const auto& e : f) {
        EXPECT_EQ(e.kind, EdgeKind::crease);
        EXPECT_NEAR(e.dihedral, 90.0f, 1e-3f);
        // A cube edge joins vertices differing in exactly one coordinate: no diagonal.
        glm::vec3 d = glm::abs(m.positions[e.b] - m.positions[e.a]);
        EXPECT_FLOAT_EQ(d.x + d.y + d.z, 1.0f);
    }
    double len = 0;
    for (const auto& pl : feature_polylines(m, f)) {
        EXPECT_EQ(pl.kind, "crease");
        for (std::size_t i = 1; i < pl.points.size(); ++i) len += glm::length(pl.points[i] - pl.points[i - 1]);
    }
    EXPECT_NEAR(len, 12.0, 1e-5);
    // Above 90 degrees nothing is a crease.
    FeatureOptions o;
    o.crease_angle = 91.0f;
    EXPECT_TRUE(feature_edges(m, o).empty());
}

TEST(FeatureEdges, MaterialBoundariesAndPlanarGroups) {
    TriangleMesh m = test::unit_cube();
    m.material_names = {"walls", "roof"};
    m.material[2] = m.material[3] = 1;  // the z = 1 face
    FeatureOptions o;
    o.crease_angle = 100.0f;
    auto f = feature_edges(m, o);
    auto c = count_kinds(f);
    EXPECT_EQ(c[EdgeKind::material], 4);
    EXPECT_EQ(int(f.size()), 4);
    auto groups = planar_face_groups(m, classify_edges(m, {}));
    EXPECT_EQ(groups.count, 6);
    for (int face = 0; face < 12; face += 2) EXPECT_EQ(groups.group[face], groups.group[face + 1]);
}

TEST(FeatureEdges, OpenQuadHasFourBoundaryEdges) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.material = {0, 0};
    m.material_names = {"default"};
    auto c = count_kinds(feature_edges(m, {}));
    EXPECT_EQ(c[EdgeKind::boundary], 4);
    EXPECT_EQ(c.size(), 1u);
    auto lines = feature_polylines(m, feature_edges(m, {}));
    ASSERT_EQ(lines.size(), 1u);  // one closed loop
    EXPECT_EQ(lines[0].points.size(), 5u);
    EXPECT_EQ(lines[0].points.front(), lines[0].points.back());
}

TEST(FeatureEdges, NonManifoldEdgeIsACrease) {
    TriangleMesh m;  // three fins sharing edge (0, 1)
    m.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 1, 4}};
    m.material = {0, 0, 0};
    m.material_names = {"default"};
    auto f = feature_edges(m, {});
    auto c = count_kinds(f);
    EXPECT_EQ(c[EdgeKind::nonmanifold], 1);
    EXPECT_EQ(c[EdgeKind::boundary], 6);
    for (const auto& pl : feature_polylines(m, f)) EXPECT_NE(pl.kind, "nonmanifold");
}

TEST(FeatureEdges, SmoothSphereHasNoneAtSixtyDegrees) {
    TriangleMesh m = test::uv_sphere(48, 1.0, test::UvLayout::closed);  // shared seam and poles
    FeatureOptions o;
    o.crease_angle = 60.0f;
    EXPECT_TRUE(feature_edges(m, o).empty());
    o.crease_angle = 1.0f;  // every edge bends by ~7.5 degrees
    EXPECT_GT(feature_edges(m, o).size(), 1000u);
    // Curved faces do not merge into one "planar" group.
    EXPECT_GT(planar_face_groups(m, classify_edges(m, {})).count, 1000);
}
