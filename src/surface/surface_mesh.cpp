#include "surface/surface_mesh.hpp"

#include <glm/geometric.hpp>

namespace penink {

SurfaceMesh mesh_from_terrain(const Terrain& t) {
    SurfaceMesh m;
    m.pos = t.pos;
    m.tri.reserve(std::size_t(t.cols > 1 ? t.cols - 1 : 0) * (t.rows > 1 ? t.rows - 1 : 0) * 2);
    for (int r = 0; r + 1 < t.rows; ++r) {
        for (int c = 0; c + 1 < t.cols; ++c) {
            const unsigned a = unsigned(t.index(c, r)), b = unsigned(t.index(c + 1, r));
            const unsigned s = unsigned(t.index(c, r + 1)), d = unsigned(t.index(c + 1, r + 1));
            if (t.valid[a] && t.valid[s] && t.valid[d]) m.tri.push_back({a, s, d});
            if (t.valid[a] && t.valid[d] && t.valid[b]) m.tri.push_back({a, d, b});
        }
    }
    compute_normals(m);
    return m;
}

void compute_normals(SurfaceMesh& m) {
    m.face_normal.resize(m.tri.size());
    std::vector<glm::vec3> sum(m.pos.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < m.tri.size(); ++i) {
        const glm::uvec3 t = m.tri[i];
        const glm::vec3 n = glm::cross(m.pos[t.y] - m.pos[t.x], m.pos[t.z] - m.pos[t.x]);
        const float len = glm::length(n);
        m.face_normal[i] = len > 0.0f ? n / len : glm::vec3(0, 0, 1);
        for (int k = 0; k < 3; ++k) sum[t[k]] += m.face_normal[i];
    }
    m.normal.resize(m.pos.size());
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const float len = glm::length(sum[i]);
        m.normal[i] = len > 1e-12f ? sum[i] / len : glm::vec3(0, 0, 1);
    }
}

}  // namespace penink
