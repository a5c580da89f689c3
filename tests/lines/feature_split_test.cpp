// split_feature_edges (crease / contour split for an eye, sharp vertices) and split_at_creases
// (one vertex per smooth fan of corners) on a unit cube, a bent sheet, a flat patch and a fin of
// three triangles on one edge. All inputs are small-integer coordinates, so positions are copied
// bit for bit and compared exactly; angles only matter against thresholds far from them
// (90 degree folds against 40 or 100, 0 degree diagonals against 40).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "lines/feature_edges.hpp"
#include "support/test_meshes.hpp"

using namespace penink;

namespace {

// A sheet bent 90 degrees along the edge 1-2 (x = 1, z = 0):
//   floor (normal +z): 0 (0,0,0), 1 (1,0,0), 2 (1,1,0), 3 (0,1,0): triangles (0,1,2), (0,2,3)
//   wall  (normal -x): 1, 4 (1,0,1), 5 (1,1,1), 2:                  triangles (1,4,5), (1,5,2)
// Consistently oriented: the floor runs the fold 1 -> 2, the wall 2 -> 1.
TriangleMesh bent_sheet() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 1}, {1, 1, 1}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
    m.material = {0, 0, 0, 0};
    m.material_names = {"default"};
    return m;
}

// A flat 2x2-quad patch in z = 0: vertex 3 r + c at (c, r, 0), 8 CCW triangles.
TriangleMesh flat_patch() {
    TriangleMesh m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m.positions.emplace_back(c, r, 0);
    for (unsigned r = 0; r < 2; ++r)
        for (unsigned c = 0; c < 2; ++c) {
            const unsigned v = 3 * r + c;
            m.triangles.emplace_back(v, v + 1, v + 4);
            m.triangles.emplace_back(v, v + 4, v + 3);
        }
    m.material.assign(8, 0);
    m.material_names = {"default"};
    return m;
}

FeatureOptions crease_at(float degrees) {
    FeatureOptions o;
    o.crease_angle = degrees;
    return o;
}

std::set<std::pair<unsigned, unsigned>> edge_set(const std::vector<MeshEdge>& edges) {
    std::set<std::pair<unsigned, unsigned>> s;
    for (const MeshEdge& e : edges) s.insert({e.a, e.b});
    return s;
}

// Every corner of the split mesh sits where the same corner of the original sat.
void expect_corners_preserved(const TriangleMesh& in, const TriangleMesh& out) {
    ASSERT_EQ(out.triangles.size(), in.triangles.size());
    for (std::size_t f = 0; f < in.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            ASSERT_LT(out.triangles[f][k], out.positions.size());
            EXPECT_EQ(out.positions[out.triangles[f][k]], in.positions[in.triangles[f][k]]) << f << " " << k;
        }
    EXPECT_EQ(out.material, in.material);
    EXPECT_EQ(out.material_names, in.material_names);
}

}  // namespace

TEST(FeatureSplit, CubeFromACornerEyeSplitsContoursFeaturesAndDropsHiddenEdges) {
    // Eye (3, 2, 1.5): x > 1, y > 1, z > 1, so +x, +y, +z face it and -x, -y, -z face away.
    const TriangleMesh m = test::unit_cube();
    const FeatureSplit s = split_feature_edges(m, classify_edges(m, {}), {3.0f, 2.0f, 1.5f});
    // Between two front faces (all at vertex 7 = (1,1,1)): +x/+y, +x/+z, +y/+z.
    EXPECT_EQ(edge_set(s.features), (std::set<std::pair<unsigned, unsigned>>{{3, 7}, {5, 7}, {6, 7}}));
    // Between a front and a back face: the hexagon outline that avoids vertices 0 and 7.
    EXPECT_EQ(edge_set(s.contours),
              (std::set<std::pair<unsigned, unsigned>>{{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}}));
    // The three edges at vertex 0 = (0,0,0) join two back faces: dropped. The face diagonals
    // (dihedral 0) are no feature at all.
    for (const MeshEdge& e : s.features) EXPECT_EQ(e.kind, EdgeKind::crease);
    for (const MeshEdge& e : s.contours) EXPECT_EQ(e.kind, EdgeKind::crease);
    // Every cube vertex lies on a crease, the dropped ones included.
    EXPECT_EQ(s.sharp, std::vector<char>(8, 1));
}

TEST(FeatureSplit, EyeOnTheOtherSideMirrorsTheSplit) {
    // Eye (-2, -1, -0.5): -x, -y, -z face it; now vertex 0's edges are features and vertex 7's
    // are dropped; the outline hexagon is the same.
    const TriangleMesh m = test::unit_cube();
    const FeatureSplit s = split_feature_edges(m, classify_edges(m, {}), {-2.0f, -1.0f, -0.5f});
    EXPECT_EQ(edge_set(s.features), (std::set<std::pair<unsigned, unsigned>>{{0, 1}, {0, 2}, {0, 4}}));
    EXPECT_EQ(edge_set(s.contours),
              (std::set<std::pair<unsigned, unsigned>>{{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}}));
}

TEST(FeatureSplit, MaterialEdgesAreNeverContoursAndNotSharp) {
    // Creases off (100 > 90 degrees); the +z face (triangles 2, 3) has its own material: its four
    // edges are material edges. With the eye of the first test +z faces it: (5,7), (6,7) join it to
    // front faces, (4,5), (4,6) to back faces; a material edge is no silhouette, so all four are
    // features, and no vertex is sharp.
    TriangleMesh m = test::unit_cube();
    m.material_names = {"walls", "roof"};
    m.material[2] = m.material[3] = 1;
    const FeatureSplit s = split_feature_edges(m, classify_edges(m, crease_at(100.0f)), {3.0f, 2.0f, 1.5f});
    EXPECT_EQ(edge_set(s.features), (std::set<std::pair<unsigned, unsigned>>{{4, 5}, {4, 6}, {5, 7}, {6, 7}}));
    EXPECT_TRUE(s.contours.empty());
    EXPECT_EQ(s.sharp, std::vector<char>(8, 0));
}

TEST(FeatureSplit, BentSheetFoldIsFeatureOrContourByEye) {
    const TriangleMesh m = bent_sheet();
    const std::vector<MeshEdge> edges = classify_edges(m, crease_at(40.0f));
    // Eye (0, 0.5, 2): above the floor (+z faces it) and at x < 1 in front of the wall (-x faces
    // it): the fold (1,2) is a feature; the 6 boundary edges are features whatever the faces do.
    FeatureSplit s = split_feature_edges(m, edges, {0.0f, 0.5f, 2.0f});
    EXPECT_TRUE(s.contours.empty());
    EXPECT_EQ(s.features.size(), 7u);
    EXPECT_EQ(s.sharp, (std::vector<char>{0, 1, 1, 0, 0, 0}));  // only the fold's ends
    // Eye (3, 0.5, 2): still above the floor but behind the wall: the fold is a contour.
    s = split_feature_edges(m, edges, {3.0f, 0.5f, 2.0f});
    EXPECT_EQ(edge_set(s.contours), (std::set<std::pair<unsigned, unsigned>>{{1, 2}}));
    EXPECT_EQ(s.features.size(), 6u);
    for (const MeshEdge& e : s.features) EXPECT_EQ(e.kind, EdgeKind::boundary);
    // Eye (3, 0.5, -2): below the floor and behind the wall: the fold joins two back faces and is
    // dropped; boundary edges (one face) are kept.
    s = split_feature_edges(m, edges, {3.0f, 0.5f, -2.0f});
    EXPECT_TRUE(s.contours.empty());
    EXPECT_EQ(s.features.size(), 6u);
    EXPECT_EQ(s.sharp, (std::vector<char>{0, 1, 1, 0, 0, 0}));
}

TEST(FeatureSplit, CubeSplitsEachCornerIntoThreeFans) {
    // crease_angle 40: the 12 cube edges (90 degrees) are creases, the 6 diagonals (0) are not.
    const TriangleMesh m = test::unit_cube();
    const TriangleMesh out = split_at_creases(m, classify_edges(m, crease_at(40.0f)));
    ASSERT_EQ(out.positions.size(), 24u);  // 8 corners x 3 faces meeting there
    expect_corners_preserved(m, out);
    std::map<std::tuple<float, float, float>, int> copies;
    for (const glm::vec3& p : out.positions) copies[{p.x, p.y, p.z}]++;
    ASSERT_EQ(copies.size(), 8u);
    for (const auto& [p, n] : copies) EXPECT_EQ(n, 3);
    // The two triangles of one face share their diagonal's two vertices; different faces share
    // none (each face is now its own 4-vertex patch).
    for (std::size_t f = 0; f < 12; ++f)
        for (std::size_t g = f + 1; g < 12; ++g) {
            int shared = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) shared += out.triangles[f][i] == out.triangles[g][j];
            EXPECT_EQ(shared, f / 2 == g / 2 ? 2 : 0) << f << " " << g;
        }
    // So the split cube's edges are 6 x 4 boundary edges and 6 smooth diagonals.
    const std::vector<MeshEdge> split_edges = classify_edges(out, crease_at(40.0f));
    EXPECT_EQ(split_edges.size(), 30u);
    EXPECT_EQ(std::count_if(split_edges.begin(), split_edges.end(),
                            [](const MeshEdge& e) { return e.kind == EdgeKind::boundary; }),
              24);
}

TEST(FeatureSplit, CubeWithoutCreasesKeepsItsVertices) {
    // crease_angle 100: no edge is sharp, every corner fan closes around its vertex.
    const TriangleMesh m = test::unit_cube();
    const TriangleMesh out = split_at_creases(m, classify_edges(m, crease_at(100.0f)));
    EXPECT_EQ(out.positions.size(), 8u);
    expect_corners_preserved(m, out);
}

TEST(FeatureSplit, FlatPatchKeepsItsVertexCount) {
    const TriangleMesh m = flat_patch();
    const std::vector<MeshEdge> edges = classify_edges(m, crease_at(40.0f));
    ASSERT_EQ(edges.size(), 16u);  // 8 boundary, 4 inner grid lines, 4 diagonals
    const TriangleMesh out = split_at_creases(m, edges);
    EXPECT_EQ(out.positions.size(), 9u);
    expect_corners_preserved(m, out);
    const FeatureSplit s = split_feature_edges(m, edges, {1.0f, 1.0f, 5.0f});
    EXPECT_EQ(s.features.size(), 8u);  // the boundary
    EXPECT_TRUE(s.contours.empty());
    EXPECT_EQ(s.sharp, std::vector<char>(9, 0));  // boundaries are not sharp
}

TEST(FeatureSplit, BentSheetSplitsOnlyTheFoldVertices) {
    const TriangleMesh m = bent_sheet();
    const TriangleMesh out = split_at_creases(m, classify_edges(m, crease_at(40.0f)));
    // Vertices are numbered in corner order (3 f + k), one per smooth fan:
    //   floor: 0, 1, 2, 3 = original 0, 1, 2, 3; wall: 4 = 1, 5 = 4, 6 = 5, 7 = 2.
    const std::vector<glm::vec3> expected = {m.positions[0], m.positions[1], m.positions[2], m.positions[3],
                                             m.positions[1], m.positions[4], m.positions[5], m.positions[2]};
    EXPECT_EQ(out.positions, expected);
    EXPECT_EQ(out.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}}));
    expect_corners_preserved(m, out);
    // Unfolded to 100 degrees the fold is smooth: nothing splits, the triangles are unchanged.
    const TriangleMesh smooth = split_at_creases(m, classify_edges(m, crease_at(100.0f)));
    EXPECT_EQ(smooth.positions, m.positions);
    EXPECT_EQ(smooth.triangles, m.triangles);
}

TEST(FeatureSplit, NonManifoldEdgeSplitsEveryFin) {
    // Three triangles on the edge 0-1 (a fin): the edge is non-manifold whatever the angles, so
    // each triangle keeps its own copies of vertices 0 and 1: 3 x 3 vertices.
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}};
    m.material = {0, 0, 0};
    m.material_names = {"default"};
    const std::vector<MeshEdge> edges = classify_edges(m, crease_at(40.0f));
    const auto fin = std::find_if(edges.begin(), edges.end(), [](const MeshEdge& e) { return e.a == 0 && e.b == 1; });
    ASSERT_NE(fin, edges.end());
    EXPECT_EQ(fin->kind, EdgeKind::nonmanifold);
    EXPECT_EQ(fin->face_count, 3);
    const TriangleMesh out = split_at_creases(m, edges);
    EXPECT_EQ(out.positions.size(), 9u);
    expect_corners_preserved(m, out);
    const FeatureSplit s = split_feature_edges(m, edges, {0.2f, 0.2f, 3.0f});
    EXPECT_EQ(s.sharp, (std::vector<char>{1, 1, 0, 0, 0}));
}
