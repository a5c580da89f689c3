#include "core/triangle_mesh.hpp"

#include <glm/common.hpp>

namespace penink {

void mesh_y_up_to_z_up(TriangleMesh& mesh) {
    for (auto& p : mesh.positions) p = glm::vec3(p.x, -p.z, p.y);
}

bool mesh_bounds(const TriangleMesh& mesh, glm::vec3& lo, glm::vec3& hi) {
    if (mesh.positions.empty()) return false;
    lo = hi = mesh.positions[0];
    for (const auto& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return true;
}

}  // namespace penink
