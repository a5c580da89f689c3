#include "scene/raycast_reference.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "surface/pn_tessellation.hpp"

namespace penink {

namespace {

// 1 for each triangle with a vertex on the mesh's boundary (an end of an edge no other triangle
// shares): both triangles of a cut-edge cell.
std::vector<std::uint8_t> boundary_triangles(const SurfaceMesh& mesh) {
    const auto key = [](unsigned a, unsigned b) { return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b); };
    std::unordered_map<std::uint64_t, int> uses;
    uses.reserve(mesh.tri.size() * 2);
    for (const glm::uvec3& t : mesh.tri)
        for (int k = 0; k < 3; ++k) ++uses[key(t[k], t[(k + 1) % 3])];
    std::vector<std::uint8_t> on_boundary(mesh.pos.size(), 0);
    for (const auto& [k, n] : uses)
        if (n == 1) on_boundary[k >> 32] = on_boundary[k & 0xffffffffu] = 1;
    std::vector<std::uint8_t> out(mesh.tri.size(), 0);
    for (std::size_t i = 0; i < mesh.tri.size(); ++i)
        out[i] = on_boundary[mesh.tri[i][0]] | on_boundary[mesh.tri[i][1]] | on_boundary[mesh.tri[i][2]];
    return out;
}

}  // namespace

std::vector<std::vector<glm::vec2>> raycast_reference(const SurfaceMesh& mesh, const Camera& camera,
                                                      const RaycastReferenceOptions& options) {
    const float s = float(std::max(1, options.rays.supersample));
    const PnTessellation tess = tessellate_pn_surface(mesh, view_projection(camera),
                                                      glm::vec2(camera.width * s, camera.height * s),
                                                      options.edge_px * s, 64);
    const std::vector<std::uint8_t> boundary = boundary_triangles(mesh);
    std::vector<std::uint8_t> cut(tess.tri.size());
    for (std::size_t t = 0; t < tess.tri.size(); ++t) cut[t] = boundary[tess.patch[t]];
    return raycast_silhouettes(tess.pos, tess.tri, cut, camera, options.rays);
}

}  // namespace penink
