#include "surface/boundary_curves.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "surface/pn_triangle.hpp"

namespace penink {

namespace {

using Edge = std::pair<unsigned, unsigned>;

// Directed boundary edges (a -> b in triangle order): their reverse belongs to no triangle.
std::map<unsigned, std::vector<unsigned>> boundary_edges(const SurfaceMesh& m) {
    std::map<Edge, int> count;
    for (const glm::uvec3& t : m.tri)
        for (int k = 0; k < 3; ++k) ++count[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    std::map<unsigned, std::vector<unsigned>> next;
    for (const glm::uvec3& t : m.tri)
        for (int k = 0; k < 3; ++k) {
            const unsigned a = t[k], b = t[(k + 1) % 3];
            if (count[{std::min(a, b), std::max(a, b)}] == 1) next[a].push_back(b);
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
