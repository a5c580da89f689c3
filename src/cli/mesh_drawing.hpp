// The mesh path of `penink render` (issue 5; Xie et al. 2007 PELs, Winkenbach & Salesin 1994
// feature lines and indication textures): OBJ/PLY/OFF mesh -> z-up world (y-up meshes rotated)
// -> camera (scene eye/target or auto-framed) -> GPU TFT pass (flat triangles) for the depth
// image -> object-space PELs, silhouettes, feature edges and textures, each split into visible
// strokes against that depth image, in the layers `pels`, `silhouettes` (+ surface mask fill),
// `feature-edges`, `textures` of a Drawing (image pixels, eye distance in mesh units).
#pragma once
#include <string>
#include <vector>

#include "cli/mesh_scene.hpp"
#include "cli/scene_drawing.hpp"
#include "input/mesh_reader.hpp"
#include "lines/feature_edges.hpp"
#include "lines/photic_extremum_lines.hpp"

namespace penink {

// CPU time of the object-space steps of one frame, milliseconds.
struct MeshLineTimings {
    double normals = 0, pel_geometry = 0, pel = 0, silhouettes = 0, features = 0, textures = 0,
           visibility = 0;
};

// The object-space lines of one frame, world frame (before hidden-line removal).
struct MeshLines {
    std::vector<ObjectPolyline> pels, silhouettes, feature_edges, textures;
    MeshLineTimings times;
};

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

// Every object-space line of the frame for the eye (and the light of `ms`, else at the eye):
// PELs and interpolated silhouettes on the crease-split mesh (PELs left out in flat-shaded
// triangles), contour creases as silhouettes, feature edges, textures.
MeshLines mesh_lines(const TriangleMesh& mesh, const MeshScene& ms, const Scene& scene, const glm::vec3& eye,
                     const Log& log);

SceneDrawing draw_mesh(const Scene& scene, GlContext& context, const Log& log);

}  // namespace penink
