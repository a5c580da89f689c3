// A triangle mesh as the mesh stages share it: vertex positions (file units, file frame until
// mesh_y_up_to_z_up rotates a y-up mesh into the z-up world of conventions.md), counter-clockwise
// triangles (front faces), and a material per triangle (OBJ `usemtl` groups; "default" when none).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace penink {

struct TriangleMesh {
    std::vector<glm::vec3> positions;       // vertex positions, file units
    std::vector<glm::uvec3> triangles;      // vertex indices, file winding (CCW = front)
    std::vector<std::uint32_t> material;    // per triangle: index into material_names
    std::vector<std::string> material_names;  // at least one entry ("default")
    std::string source;                     // file it came from (for messages)
};

// Rotates a y-up mesh into the z-up world frame of conventions.md: (x, y, z) -> (x, -z, y).
void mesh_y_up_to_z_up(TriangleMesh& mesh);

// Axis-aligned bounds of the positions; false for an empty mesh.
bool mesh_bounds(const TriangleMesh& mesh, glm::vec3& lo, glm::vec3& hi);

}  // namespace penink
