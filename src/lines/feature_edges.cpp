#include "lines/feature_edges.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

namespace penink {
namespace {

glm::vec3 face_normal(const TriangleMesh& m, std::size_t f) {
    const glm::uvec3& t = m.triangles[f];
    glm::vec3 c = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    float len = glm::length(c);
    return len > 0.0f ? c / len : glm::vec3(0, 0, 1);
}

float angle_deg(const glm::vec3& a, const glm::vec3& b) {
    return float(std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)) * 180.0 / M_PI);
}

EdgeKind classify(const TriangleMesh& m, const MeshEdge& e, const FeatureOptions& o) {
    if (e.face_count == 1) return o.boundaries ? EdgeKind::boundary : EdgeKind::none;
    if (e.face_count > 2) return EdgeKind::nonmanifold;
    if (e.dihedral > o.crease_angle) return EdgeKind::crease;
    if (o.material_boundaries && m.material[e.face0] != m.material[e.face1]) return EdgeKind::material;
    return EdgeKind::none;
}

}  // namespace

const char* edge_kind_name(EdgeKind kind) {
    switch (kind) {
        case EdgeKind::crease: return "crease";
        case EdgeKind::boundary: return "boundary";
        case EdgeKind::material: return "material";
        case EdgeKind::nonmanifold: return "nonmanifold";
        default: return "";
    }
}

std::vector<MeshEdge> classify_edges(const TriangleMesh& mesh, const FeatureOptions& options) {
    std::vector<std::pair<std::uint64_t, int>> half;  // (edge key, face)
    half.reserve(mesh.triangles.size() * 3);
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            unsigned i = mesh.triangles[f][k], j = mesh.triangles[f][(k + 1) % 3];
            if (i > j) std::swap(i, j);
            half.push_back({(std::uint64_t(i) << 32) | j, int(f)});
        }
    std::sort(half.begin(), half.end());
    std::vector<MeshEdge> edges;
    for (std::size_t s = 0; s < half.size();) {
        std::size_t e = s;
        while (e < half.size() && half[e].first == half[s].first) ++e;
        MeshEdge me;
        me.a = unsigned(half[s].first >> 32);
        me.b = unsigned(half[s].first & 0xffffffffu);
        me.face0 = half[s].second;
        me.face1 = e - s > 1 ? half[s + 1].second : -1;
        me.face_count = int(e - s);
        if (me.face1 >= 0) me.dihedral = angle_deg(face_normal(mesh, me.face0), face_normal(mesh, me.face1));
        me.kind = classify(mesh, me, options);
        edges.push_back(me);
        s = e;
    }
    return edges;
}

std::vector<MeshEdge> feature_edges(const TriangleMesh& mesh, const FeatureOptions& options) {
    std::vector<MeshEdge> all = classify_edges(mesh, options), out;
    std::copy_if(all.begin(), all.end(), std::back_inserter(out),
                 [](const MeshEdge& e) { return e.kind != EdgeKind::none; });
    return out;
}

std::vector<ObjectPolyline> feature_polylines(const TriangleMesh& mesh,
                                              const std::vector<MeshEdge>& features) {
    // Group by (kind, material) so each polyline has one kind and material; chain by vertex.
    std::map<std::pair<std::string, std::uint32_t>, std::vector<ObjectSegment>> groups;
    for (const MeshEdge& e : features) {
        EdgeKind k = e.kind == EdgeKind::nonmanifold ? EdgeKind::crease : e.kind;
        ObjectSegment s{mesh.positions[e.a], mesh.positions[e.b], 1.0f, e.a, e.b};
        groups[{edge_kind_name(k), mesh.material[e.face0]}].push_back(s);
    }
    std::vector<ObjectPolyline> out;
    for (auto& [key, segs] : groups) {
        for (ObjectPolyline& pl : chain_segments(segs, key.first)) {
            pl.material = mesh.material_names.at(key.second);
            out.push_back(std::move(pl));
        }
    }
    return out;
}

FaceGroups planar_face_groups(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges,
                              float planar_angle) {
    // Flood fill from each unassigned face (in index order) across non-feature manifold edges,
    // accepting faces whose normal is within planar_angle of the seed face's normal (so a finely
    // tessellated curved surface does not drift into one group).
    std::vector<std::vector<int>> adj(mesh.triangles.size());
    for (const MeshEdge& e : edges) {
        if (e.kind != EdgeKind::none || e.face_count != 2) continue;
        if (mesh.material[e.face0] != mesh.material[e.face1]) continue;
        adj[e.face0].push_back(e.face1);
        adj[e.face1].push_back(e.face0);
    }
    FaceGroups g;
    g.group.assign(mesh.triangles.size(), -1);
    std::vector<int> stack;
    for (std::size_t seed = 0; seed < mesh.triangles.size(); ++seed) {
        if (g.group[seed] >= 0) continue;
        const glm::vec3 n0 = face_normal(mesh, seed);
        g.group[seed] = g.count;
        stack.assign(1, int(seed));
        while (!stack.empty()) {
            int f = stack.back();
            stack.pop_back();
            for (int h : adj[f]) {
                if (g.group[h] >= 0 || angle_deg(n0, face_normal(mesh, h)) > planar_angle) continue;
                g.group[h] = g.count;
                stack.push_back(h);
            }
        }
        ++g.count;
    }
    return g;
}

namespace {

bool is_sharp(EdgeKind k) { return k == EdgeKind::crease || k == EdgeKind::nonmanifold; }

bool faces_eye(const TriangleMesh& m, int f, const glm::vec3& eye) {
    const glm::uvec3& t = m.triangles[f];
    const glm::vec3 &a = m.positions[t.x], &b = m.positions[t.y], &c = m.positions[t.z];
    return glm::dot(glm::cross(b - a, c - a), eye - a) > 0.0f;
}

unsigned find_root(std::vector<unsigned>& parent, unsigned i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// Corner (3 * face + k) of face f at vertex v.
unsigned corner_of(const TriangleMesh& m, int f, unsigned v) {
    const glm::uvec3& t = m.triangles[f];
    return 3u * unsigned(f) + (t.x == v ? 0u : t.y == v ? 1u : 2u);
}

}  // namespace

FeatureSplit split_feature_edges(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges,
                                 const glm::vec3& eye) {
    FeatureSplit out;
    out.sharp.assign(mesh.positions.size(), 0);
    for (const MeshEdge& e : edges) {
        if (e.kind == EdgeKind::none) continue;
        if (is_sharp(e.kind)) out.sharp[e.a] = out.sharp[e.b] = 1;
        if (e.face_count == 2 && !faces_eye(mesh, e.face0, eye) && !faces_eye(mesh, e.face1, eye))
            continue;  // between two faces turned away: hidden on a closed surface
        const bool contour = is_sharp(e.kind) && e.face0 >= 0 && e.face1 >= 0 &&
                             faces_eye(mesh, e.face0, eye) != faces_eye(mesh, e.face1, eye);
        (contour ? out.contours : out.features).push_back(e);
    }
    return out;
}

TriangleMesh split_at_creases(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges) {
    std::vector<unsigned> parent(mesh.triangles.size() * 3);
    for (unsigned i = 0; i < parent.size(); ++i) parent[i] = i;
    for (const MeshEdge& e : edges) {  // join the corners of smooth manifold edges
        if (is_sharp(e.kind) || e.face_count != 2) continue;
        for (unsigned v : {e.a, e.b}) {
            const unsigned r0 = find_root(parent, corner_of(mesh, e.face0, v));
            const unsigned r1 = find_root(parent, corner_of(mesh, e.face1, v));
            parent[std::max(r0, r1)] = std::min(r0, r1);
        }
    }
    TriangleMesh out = mesh;
    out.positions.clear();
    std::vector<unsigned> index(parent.size(), ~0u);
    for (unsigned c = 0; c < parent.size(); ++c) {  // new vertices in corner order: deterministic
        const unsigned r = find_root(parent, c);
        if (index[r] == ~0u) {
            index[r] = unsigned(out.positions.size());
            out.positions.push_back(mesh.positions[mesh.triangles[c / 3][c % 3]]);
        }
        out.triangles[c / 3][c % 3] = index[r];
    }
    return out;
}

}  // namespace penink
