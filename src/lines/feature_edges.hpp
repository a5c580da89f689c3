// Architectural feature edges of a TriangleMesh (Winkenbach & Salesin 1994, sec. 3-4): creases
// where the dihedral angle between the unit normals of two adjacent faces exceeds crease_angle
// (degrees), boundary edges (one face), material boundaries (faces with different OBJ usemtl
// materials) and non-manifold edges (three or more faces, drawn as creases). Also the planar face
// groups bounded by those edges, which carry the indication textures. World frame, mesh units.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/triangle_mesh.hpp"
#include "lines/photic_extremum_lines.hpp"

namespace penink {

enum class EdgeKind : std::uint8_t { none, crease, boundary, material, nonmanifold };

// "crease", "boundary", "material", "nonmanifold" ("" for none).
const char* edge_kind_name(EdgeKind kind);

struct MeshEdge {
    unsigned a = 0, b = 0;        // vertex indices, a < b
    int face0 = -1, face1 = -1;   // first two incident faces (-1 when missing)
    int face_count = 0;
    float dihedral = 0.0f;        // degrees between the normals of face0 and face1 (0 if < 2 faces)
    EdgeKind kind = EdgeKind::none;
};

struct FeatureOptions {
    float crease_angle = 30.0f;  // degrees; dihedral angles above it are creases
    bool boundaries = true;
    bool material_boundaries = true;
};

// Every edge of the mesh once (sorted by (a, b)), classified.
std::vector<MeshEdge> classify_edges(const TriangleMesh& mesh, const FeatureOptions& options = {});

// The feature edges only (kind != none).
std::vector<MeshEdge> feature_edges(const TriangleMesh& mesh, const FeatureOptions& options = {});

// Feature edges chained into polylines of one kind each (non-manifold edges get kind "crease");
// material = material name of the edge's first face.
std::vector<ObjectPolyline> feature_polylines(const TriangleMesh& mesh,
                                              const std::vector<MeshEdge>& features);

// Faces connected across non-feature manifold edges whose normals differ by at most
// planar_angle degrees and that share a material: one group id per face, 0..count-1.
struct FaceGroups {
    std::vector<int> group;  // per face
    int count = 0;
};
FaceGroups planar_face_groups(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges,
                              float planar_angle = 1.0f);

// Crease / contour split of the feature edges for an eye: a crease or non-manifold edge between
// a face turned toward the eye and one turned away is a silhouette, not a feature edge.
// Edges between two faces turned away are left out (hidden on a closed surface; the depth test
// alone lets a few pixels of them through where they meet the outline).
// `sharp` marks the vertices on a crease or non-manifold edge.
struct FeatureSplit {
    std::vector<MeshEdge> features, contours;
    std::vector<char> sharp;  // per vertex
};
FeatureSplit split_feature_edges(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges,
                                 const glm::vec3& eye);

// The mesh with its vertices split at crease and non-manifold edges (one vertex per smooth fan
// of corners), so vertex normals never average across a crease; same triangles and materials.
TriangleMesh split_at_creases(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges);

}  // namespace penink
