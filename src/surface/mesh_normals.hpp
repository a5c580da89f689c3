// Vertex normals of a TriangleMesh (core/triangle_mesh.hpp): unit face normals, area- or
// angle-weighted vertex normals (Max 1999 / Thuermer & Wuethrich 1998), Laplacian normal
// smoothing for noisy scans (umbrella average of neighbour normals, k iterations), the Gaussian
// normal filter PELs are extracted after (Xie et al., "Photic Extremum Lines": the normal field is
// smoothed before the illumination is differentiated, since PELs take third derivatives of the
// surface), plus the conversion to the renderer's SurfaceMesh. Units and frame are the mesh's own.
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

// Mean length of the triangles' edges (each interior edge counted twice); 0 with no triangles.
float mean_edge_length(const TriangleMesh& mesh);

// n_i <- normalize(sum_j w_j n_j) over the vertices j within 2 sigma of p_i that are reached
// from i through edges (neighbours within 2 sigma of p_i): the surface neighbourhood, so two
// sheets close in space (a thin part) do not mix. w_j = a_j exp(-|p_j - p_i|^2 / (2 sigma^2))
// (1 - c . t_j), a_j = a third of the area of j's triangles, t_j = p_j - p_i in the tangent plane
// of n_i, c chosen so that sum w_j t_j = 0 (local linear correction: on an irregular mesh a plain
// Gaussian mean tilts every normal towards its patch's centroid, and PELs, third derivatives,
// turn that tilt into spurious lines). One pass; sigma in mesh units; sigma <= 0 returns the
// input. Cost: the neighbourhood's size per vertex (about pi (2 sigma / edge)^2 vertices).
std::vector<glm::vec3> gaussian_filter_normals(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals,
                                               float sigma);

// SurfaceMesh (pos, tri, face and vertex normals) for the renderer; normals as given.
SurfaceMesh surface_mesh_from(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals);

}  // namespace penink
