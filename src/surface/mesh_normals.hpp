// Vertex normals of a TriangleMesh (core/triangle_mesh.hpp): unit face normals, area- or
// angle-weighted vertex normals (Max 1999 / Thuermer & Wuethrich 1998), and Laplacian normal
// smoothing for noisy scans (umbrella average of neighbour normals, k iterations), plus the
// conversion to the renderer's SurfaceMesh. Units and frame are the mesh's own.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "core/triangle_mesh.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

enum class NormalWeighting { area, angle };

// Unit normal per triangle (counter-clockwise = front); (0, 0, 1) for a degenerate triangle.
std::vector<glm::vec3> mesh_face_normals(const TriangleMesh& mesh);

// Unit normal per vertex: sum of incident face normals weighted by face area or by the corner
// angle at the vertex. A vertex in no triangle gets (0, 0, 1).
std::vector<glm::vec3> mesh_vertex_normals(const TriangleMesh& mesh,
                                           NormalWeighting weighting = NormalWeighting::area);

// `iterations` passes of n_i <- normalize((1 - lambda) n_i + lambda * mean(n_j, j ~ i)) over
// the edge neighbours j of i; iterations = 0 returns the input.
std::vector<glm::vec3> smooth_vertex_normals(const TriangleMesh& mesh, std::vector<glm::vec3> normals,
                                             int iterations, float lambda = 0.5f);

// SurfaceMesh (pos, tri, face and vertex normals) for the renderer; normals as given.
SurfaceMesh surface_mesh_from(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals);

}  // namespace penink
