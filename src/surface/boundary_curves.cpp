#include "surface/boundary_curves.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

#include "surface/pn_triangle.hpp"

namespace penink {

namespace {

std::uint64_t edge_key(unsigned a, unsigned b) {
    return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// Directed boundary edges (a -> b in triangle order): their reverse belongs to no triangle.
// Undirected edges are counted by sorting their keys (a mesh's edges, most of them shared).
std::map<unsigned, std::vector<unsigned>> boundary_edges(const SurfaceMesh& m) {
    std::vector<std::uint64_t> keys;
    keys.reserve(m.tri.size() * 3);
    for (const glm::uvec3& t : m.tri)
        for (int k = 0; k < 3; ++k) keys.push_back(edge_key(t[k], t[(k + 1) % 3]));
    std::sort(keys.begin(), keys.end());
    const auto once = [&](std::uint64_t key) {
        const auto range = std::equal_range(keys.begin(), keys.end(), key);
        return range.second - range.first == 1;
    };
    std::map<unsigned, std::vector<unsigned>> next;
    for (const glm::uvec3& t : m.tri)
        for (int k = 0; k < 3; ++k) {
            const unsigned a = t[k], b = t[(k + 1) % 3];
            if (once(edge_key(a, b))) next[a].push_back(b);
        }
    return next;
}

// Points of the PN edge curve a -> b (excluding b), `samples` of them.
void append_edge_curve(const SurfaceMesh& m, unsigned a, unsigned b, int samples, std::vector<glm::vec3>& out) {
    const PnPatch p = pn_patch(m.pos[a], m.pos[b], m.pos[b], m.normal[a], m.normal[b], m.normal[b]);
    for (int s = 0; s < samples; ++s) {
        const float t = float(s) / float(samples);
        out.push_back(pn_position(p, glm::vec3(1.0f - t, t, 0.0f)));
    }
}

}  // namespace

std::vector<std::vector<glm::vec3>> boundary_polylines(const SurfaceMesh& mesh, int samples) {
    std::map<unsigned, std::vector<unsigned>> next = boundary_edges(mesh);
    std::vector<std::vector<glm::vec3>> out;
    for (auto& [start, targets] : next) {
        while (!targets.empty()) {
            std::vector<glm::vec3> line;
            unsigned cur = start;
            for (;;) {
                auto it = next.find(cur);
                if (it == next.end() || it->second.empty()) break;
                const unsigned nxt = it->second.back();
                it->second.pop_back();
                append_edge_curve(mesh, cur, nxt, samples, line);
                cur = nxt;
                if (cur == start) break;
            }
            line.push_back(mesh.pos[cur]);
            out.push_back(std::move(line));
        }
    }
    return out;
}

}  // namespace penink
