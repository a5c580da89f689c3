#include "surface/pn_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

namespace penink {

namespace {

constexpr int gl_max_level = 64;

float edge_level(const glm::vec4& a, const glm::vec4& b, glm::vec2 viewport, float target, float max_level) {
    if (a.w <= 0.0f || b.w <= 0.0f) return max_level;
    const auto px = [&](const glm::vec4& c) { return (glm::vec2(c) / c.w * 0.5f + 0.5f) * viewport; };
    return std::clamp(std::ceil(glm::distance(px(a), px(b)) / target), 1.0f, max_level);
}

bool outside_frustum(const std::array<glm::vec4, 10>& c) {
    for (int axis = 0; axis < 3; ++axis) {
        bool all_low = true, all_high = true;
        for (const glm::vec4& p : c) {
            all_low = all_low && p[axis] < -p.w;
            all_high = all_high && p[axis] > p.w;
        }
        if (all_low || all_high) return true;
    }
    return false;
}

glm::vec3 corner(int c) { return glm::vec3(c == 0, c == 1, c == 2); }

// Corner c of ring k of an inner level n: the outer triangle shrunk by 2k/(3n) per ring (the
// intersection of the perpendiculars through the first subdivision points, GL spec 11.2.2.1).
glm::vec3 ring_corner(int c, int k, int n) {
    const float o = 2.0f * float(k) / (3.0f * float(n));
    glm::vec3 b(o);
    b[c] = 1.0f - 2.0f * o;
    return b;
}

struct Builder {
    BaryTriangulation out;
    std::uint32_t add(glm::vec3 b, int edge, int step) {
        out.bary.push_back(b), out.edge.push_back(edge), out.step.push_back(step);
        return std::uint32_t(out.bary.size() - 1);
    }
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const glm::vec3 pa = out.bary[a], pb = out.bary[b], pc = out.bary[c];
        const float cross = (pb.y - pa.y) * (pc.z - pa.z) - (pb.z - pa.z) * (pc.y - pa.y);
        if (std::abs(cross) < 1e-9f) return;
        if (cross > 0) out.tri.push_back({a, b, c});
        else out.tri.push_back({a, c, b});
    }
};

using Sides = std::array<std::vector<std::uint32_t>, 3>;  // side s: corner s -> corner s+1, inclusive

Sides outer_ring(Builder& bld, const std::array<int, 3>& outer) {
    std::array<std::uint32_t, 3> cs;
    for (int c = 0; c < 3; ++c) cs[c] = bld.add(corner(c), 3 + c, 0);
    Sides sides;
    for (int s = 0; s < 3; ++s) {
        const int e = (s + 2) % 3, m = outer[e], t = (s + 1) % 3;
        sides[s].push_back(cs[s]);
        for (int j = 1; j < m; ++j) {
            const float f = float(j) / float(m);
            sides[s].push_back(bld.add(corner(s) * (1.0f - f) + corner(t) * f, e, s < t ? j : m - j));
        }
        sides[s].push_back(cs[t]);
    }
    return sides;
}

Sides inner_ring(Builder& bld, int k, int n) {
    const int segs = n - 2 * k;
    Sides sides;
    if (segs == 0) {
        const std::uint32_t centre = bld.add(glm::vec3(1.0f / 3.0f), -1, 0);
        for (auto& s : sides) s = {centre};
        return sides;
    }
    std::array<std::uint32_t, 3> cs;
    for (int c = 0; c < 3; ++c) cs[c] = bld.add(ring_corner(c, k, n), -1, 0);
    for (int s = 0; s < 3; ++s) {
        const int t = (s + 1) % 3;
        sides[s].push_back(cs[s]);
        for (int j = 1; j < segs; ++j) {
            const float f = float(j) / float(segs);
            sides[s].push_back(bld.add(ring_corner(s, k, n) * (1.0f - f) + ring_corner(t, k, n) * f, -1, 0));
        }
        sides[s].push_back(cs[t]);
    }
    return sides;
}

// Triangulates the strip between an outer side O (m segments) and the inner side I (q segments,
// q = 0: one point) by advancing along whichever has the nearer next point; inner point j sits
// at (j + 1) / (q + 2) of the side.
void zip(Builder& bld, const std::vector<std::uint32_t>& o, const std::vector<std::uint32_t>& in) {
    const int m = int(o.size()) - 1, q = int(in.size()) - 1;
    int i = 0, j = 0;
    while (i < m || j < q) {
        const float next_o = i < m ? float(i + 1) / float(m) : 2.0f;
        const float next_i = j < q ? float(j + 2) / float(q + 2) : 2.0f;
        if (next_o <= next_i) bld.triangle(o[i], o[i + 1], in[j]), ++i;
        else bld.triangle(o[i], in[j + 1], in[j]), ++j;
    }
}

}  // namespace

PnLevels pn_patch_levels(const PnPatch& patch, const glm::mat4& view_proj, glm::vec2 viewport,
                         float target_edge_px, int max_level) {
    std::array<glm::vec4, 10> c;
    for (int i = 0; i < 10; ++i) c[i] = view_proj * glm::vec4(patch.b[i], 1.0f);
    PnLevels levels;
    if (outside_frustum(c)) {
        levels.culled = true;
        return levels;
    }
    const float top = float(std::clamp(max_level, 1, gl_max_level));
    levels.outer[0] = int(edge_level(c[1], c[2], viewport, target_edge_px, top));
    levels.outer[1] = int(edge_level(c[2], c[0], viewport, target_edge_px, top));
    levels.outer[2] = int(edge_level(c[0], c[1], viewport, target_edge_px, top));
    levels.inner = std::max({levels.outer[0], levels.outer[1], levels.outer[2]});
    return levels;
}

BaryTriangulation tessellate_unit_triangle(const PnLevels& levels) {
    Builder bld;
    if (levels.culled) return bld.out;
    std::array<int, 3> outer;
    for (int e = 0; e < 3; ++e) outer[e] = std::clamp(levels.outer[e], 1, gl_max_level);
    int n = std::clamp(levels.inner, 1, gl_max_level);
    const bool all_one = outer[0] == 1 && outer[1] == 1 && outer[2] == 1;
    if (n == 1 && !all_one) n = 2;  // inner 1 is treated as 1 + epsilon, rounded up
    Sides prev = outer_ring(bld, outer);
    if (n == 1) {
        bld.triangle(prev[0][0], prev[1][0], prev[2][0]);
        return bld.out;
    }
    for (int k = 1; n - 2 * k >= 0; ++k) {
        Sides ring = inner_ring(bld, k, n);
        for (int s = 0; s < 3; ++s) zip(bld, prev[s], ring[s]);
        if (n - 2 * k == 1) bld.triangle(ring[0][0], ring[1][0], ring[2][0]);
        prev = std::move(ring);
    }
    return bld.out;
}

namespace {

struct EdgeKey {
    std::uint32_t a, b;
    int step;
    bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b && step == o.step; }
};
struct EdgeKeyHash {
    std::size_t operator()(const EdgeKey& k) const {
        std::uint64_t h = (std::uint64_t(k.a) << 32 | k.b) * 0x9E3779B97F4A7C15ull;
        return std::size_t(h ^ (std::uint64_t(std::uint32_t(k.step)) * 0xC2B2AE3D27D4EB4Full));
    }
};

struct Welder {
    const SurfaceMesh& mesh;
    PnTessellation out;
    std::vector<std::int64_t> corner_index;
    std::unordered_map<EdgeKey, std::uint32_t, EdgeKeyHash> edge_index;

    explicit Welder(const SurfaceMesh& m) : mesh(m), corner_index(m.pos.size(), -1) {}

    std::uint32_t vertex(const PnPatch& patch, const glm::uvec3& t, const BaryTriangulation& bt,
                         std::size_t i, const PnLevels& lv) {
        const int e = bt.edge[i];
        std::int64_t* slot = nullptr;
        std::uint32_t found = 0;
        if (e >= 3) {
            slot = &corner_index[t[e - 3]];
            if (*slot >= 0) return std::uint32_t(*slot);
        } else if (e >= 0) {
            const int lo = e == 0 ? 1 : 0, hi = e == 2 ? 1 : 2;
            const std::uint32_t ga = t[lo], gb = t[hi];
            const EdgeKey key = ga < gb ? EdgeKey{ga, gb, bt.step[i]} : EdgeKey{gb, ga, lv.outer[e] - bt.step[i]};
            auto [it, inserted] = edge_index.try_emplace(key, std::uint32_t(out.pos.size()));
            if (!inserted) return it->second;
        }
        found = std::uint32_t(out.pos.size());
        out.pos.push_back(pn_position(patch, bt.bary[i]));
        out.normal.push_back(pn_normal(patch, bt.bary[i]));
        if (slot) *slot = found;
        return found;
    }

    void add_patch(std::uint32_t index, const PnPatch& patch, const PnLevels& lv) {
        const BaryTriangulation bt = tessellate_unit_triangle(lv);
        const glm::uvec3 t = mesh.tri[index];
        std::vector<std::uint32_t> ids(bt.bary.size());
        for (std::size_t i = 0; i < bt.bary.size(); ++i) ids[i] = vertex(patch, t, bt, i, lv);
        for (const glm::uvec3& tr : bt.tri) {
            out.tri.push_back({ids[tr.x], ids[tr.y], ids[tr.z]});
            out.patch.push_back(index);
        }
    }
};

PnPatch patch_of(const SurfaceMesh& mesh, const glm::uvec3& t) {
    return pn_patch(mesh.pos[t.x], mesh.pos[t.y], mesh.pos[t.z], glm::normalize(mesh.normal[t.x]),
                    glm::normalize(mesh.normal[t.y]), glm::normalize(mesh.normal[t.z]));
}

}  // namespace

PnTessellation tessellate_pn_surface(const SurfaceMesh& mesh, const glm::dmat4& view_proj,
                                     glm::vec2 viewport, float target_edge_px, int max_level) {
    Welder w(mesh);
    const glm::mat4 vp(view_proj);
    for (std::uint32_t i = 0; i < mesh.tri.size(); ++i) {
        const PnPatch patch = patch_of(mesh, mesh.tri[i]);
        w.add_patch(i, patch, pn_patch_levels(patch, vp, viewport, target_edge_px, max_level));
    }
    return std::move(w.out);
}

PnTessellation tessellate_pn_surface_uniform(const SurfaceMesh& mesh, int level) {
    Welder w(mesh);
    PnLevels lv;
    level = std::clamp(level, 1, gl_max_level);
    lv.outer = {level, level, level};
    lv.inner = level;
    for (std::uint32_t i = 0; i < mesh.tri.size(); ++i) w.add_patch(i, patch_of(mesh, mesh.tri[i]), lv);
    return std::move(w.out);
}

}  // namespace penink
