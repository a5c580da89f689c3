#include "support/test_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include <glm/geometric.hpp>

namespace penink::test {

namespace {

void one_material(TriangleMesh& m) {
    m.material.assign(m.triangles.size(), 0);
    m.material_names = {"default"};
}

}  // namespace

TriangleMesh unit_cube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    m.material.assign(12, 0);
    m.material_names = {"default"};
    return m;
}

TriangleMesh uv_sphere(int n, double radius, UvLayout layout, const RadialBump& bump) {
    TriangleMesh m;
    const int rings = n / 2;
    const auto vertex = [&](int i, int j) {
        const double v = M_PI * i / rings, u = 2 * M_PI * j / n;
        const double rho = bump ? radius + bump(u, v) : radius;
        m.positions.emplace_back(rho * std::sin(v) * std::cos(u), rho * std::sin(v) * std::sin(u), rho * std::cos(v));
    };
    if (layout == UvLayout::grid) {
        for (int i = 0; i <= rings; ++i)
            for (int j = 0; j <= n; ++j) vertex(i, j);
        const auto id = [&](int i, int j) { return unsigned(i * (n + 1) + j); };
        for (int i = 0; i < rings; ++i)
            for (int j = 0; j < n; ++j) {
                m.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
                m.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
            }
    } else {
        m.positions.emplace_back(0.0, 0.0, radius);
        for (int i = 1; i < rings; ++i)
            for (int j = 0; j < n; ++j) vertex(i, j);
        m.positions.emplace_back(0.0, 0.0, -radius);
        const auto id = [&](int i, int j) { return unsigned(1 + (i - 1) * n + (j % n)); };
        const unsigned south = unsigned(m.positions.size() - 1);
        for (int j = 0; j < n; ++j) {
            m.triangles.emplace_back(0, id(1, j), id(1, j + 1));
            m.triangles.emplace_back(south, id(rings - 1, j + 1), id(rings - 1, j));
            for (int i = 1; i + 1 < rings; ++i) {
                m.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
                m.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
            }
        }
    }
    one_material(m);
    return m;
}

TriangleMesh icosphere(int level, float r) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    TriangleMesh m;
    m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::uint64_t, unsigned> mid;
        auto midpoint = [&](unsigned a, unsigned b) {
            std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            m.positions.push_back(0.5f * (m.positions[a] + m.positions[b]));
            return mid[key] = unsigned(m.positions.size() - 1);
        };
        std::vector<glm::uvec3> next;
        for (auto f : m.triangles) {
            unsigned ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
            next.insert(next.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
        }
        m.triangles = next;
    }
    for (auto& p : m.positions) p = r * glm::normalize(p);
    one_material(m);
    return m;
}

std::vector<glm::vec3> radial_normals(const TriangleMesh& m) {
    std::vector<glm::vec3> n;
    for (const auto& p : m.positions) n.push_back(glm::normalize(p));
    return n;
}

std::vector<glm::vec3> noisy_normals(std::vector<glm::vec3> n, float amp, std::uint64_t seed) {
    auto next = [&seed]() {
        std::uint64_t z = (seed += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return float((z ^ (z >> 31)) >> 11) / float(1ull << 53) * 2.0f - 1.0f;
    };
    for (auto& v : n) v = glm::normalize(v + amp * glm::vec3(next(), next(), next()));
    return n;
}

}  // namespace penink::test
