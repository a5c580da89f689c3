// Triangle surface with per-face and per-vertex normals. From a Terrain: two counter-clockwise
// (seen from above, z up) triangles per grid cell split along the NW-SE diagonal, a triangle kept
// when its three nodes hold data; vertex i is grid node i (local metres, world frame).
// Vertex normal = normalised sum of the unit normals of incident faces (as in Mower, "Concurrent Drainage Network Rendering").
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "input/terrain.hpp"

namespace penink {

struct SurfaceMesh {
    std::vector<glm::vec3> pos;          // vertex positions
    std::vector<glm::vec3> normal;       // unit vertex normals
    std::vector<glm::uvec3> tri;         // counter-clockwise vertex indices
    std::vector<glm::vec3> face_normal;  // unit face normals, one per triangle
};

SurfaceMesh mesh_from_terrain(const Terrain& terrain);

// Fills face_normal and normal from pos and tri. A vertex in no triangle gets (0, 0, 1).
void compute_normals(SurfaceMesh& mesh);

}  // namespace penink
