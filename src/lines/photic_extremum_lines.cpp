#include "lines/photic_extremum_lines.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "core/stopwatch.hpp"

namespace penink {
namespace {

std::uint64_t edge_key(unsigned i, unsigned j) {
    if (i > j) std::swap(i, j);
    return (std::uint64_t(i) << 32) | j;
}

float cot(const glm::vec3& at, const glm::vec3& a, const glm::vec3& b) {
    glm::vec3 u = a - at, v = b - at;
    float s = glm::length(glm::cross(u, v));
    return s > 0.0f ? glm::dot(u, v) / s : 0.0f;
}

// Mixed Voronoi areas of the three corners of triangle p (Meyer et al. 2001, fig. 4).
glm::vec3 mixed_areas(const glm::vec3 p[3], float area) {
    for (int i = 0; i < 3; ++i) {
        if (glm::dot(p[(i + 1) % 3] - p[i], p[(i + 2) % 3] - p[i]) < 0.0f) {  // obtuse at i
            glm::vec3 w(area / 4.0f);
            w[i] = area / 2.0f;
            return w;
        }
    }
    glm::vec3 w;
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 &pj = p[(i + 1) % 3], &pk = p[(i + 2) % 3];
        float dij = glm::dot(pj - p[i], pj - p[i]), dik = glm::dot(pk - p[i], pk - p[i]);
        w[i] = (dij * cot(pk, p[i], pj) + dik * cot(pj, p[i], pk)) / 8.0f;
    }
    return w;
}

// A zero crossing of a per-vertex scalar on edge (i, j): position parameter from the lower
// index so both triangles sharing the edge compute the same bits.
struct Crossing {
    unsigned lo, hi;
    float t;
};

// The two edges of triangle t where s changes sign (s >= 0 counts as positive); false if none.
bool triangle_crossings(const glm::uvec3& t, const std::vector<float>& s, Crossing out[2]) {
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        unsigned i = t[k], j = t[(k + 1) % 3];
        if ((s[i] >= 0.0f) == (s[j] >= 0.0f)) continue;
        if (i > j) std::swap(i, j);
        out[n++] = {i, j, s[i] / (s[i] - s[j])};
    }
    return n == 2;
}

template <class T>
T lerp_at(const std::vector<T>& v, const Crossing& c) {
    return v[c.lo] + c.t * (v[c.hi] - v[c.lo]);
}

std::vector<float> directional(const std::vector<glm::vec3>& grad, const std::vector<glm::vec3>& w) {
    std::vector<float> d(grad.size());
    for (std::size_t i = 0; i < grad.size(); ++i) d[i] = glm::dot(grad[i], w[i]);
    return d;
}

void illumination(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals,
                  const glm::vec3& eye, const PelOptions& o, std::vector<float>& phi) {
    phi.resize(mesh.positions.size());
    const glm::vec3 fixed = glm::length(o.light_dir) > 0.0f ? glm::normalize(o.light_dir) : glm::vec3(0, 0, 1);
    for (std::size_t i = 0; i < phi.size(); ++i) {
        glm::vec3 l = o.light_at_eye ? glm::normalize(eye - mesh.positions[i]) : fixed;
        float d = glm::dot(normals[i], l);
        phi[i] = o.clamp_diffuse ? std::max(0.0f, d) : d;
    }
}

void normalise_gradient(const std::vector<glm::vec3>& grad, PelField& f) {
    f.g.resize(grad.size());
    f.w.resize(grad.size());
    f.max_gradient = 0.0f;
    for (std::size_t i = 0; i < grad.size(); ++i) {
        f.g[i] = glm::length(grad[i]);
        f.max_gradient = std::max(f.max_gradient, f.g[i]);
        f.w[i] = f.g[i] > 0.0f ? grad[i] / f.g[i] : glm::vec3(0.0f);
    }
    if (f.max_gradient > 0.0f)
        for (float& g : f.g) g /= f.max_gradient;
}

std::vector<ObjectSegment> extract_pels(const TriangleMesh& mesh, const PelField& f, float tau) {
    std::vector<ObjectSegment> out;
    Crossing c[2];
    for (const glm::uvec3& t : mesh.triangles) {
        if (f.g[t.x] == 0.0f || f.g[t.y] == 0.0f || f.g[t.z] == 0.0f) continue;  // PEL undefined
        if (!triangle_crossings(t, f.dw, c)) continue;
        if (lerp_at(f.dw2, c[0]) >= 0.0f || lerp_at(f.dw2, c[1]) >= 0.0f) continue;  // not a maximum
        float strength = 0.5f * (lerp_at(f.g, c[0]) + lerp_at(f.g, c[1]));
        if (strength < tau) continue;
        out.push_back({lerp_at(mesh.positions, c[0]), lerp_at(mesh.positions, c[1]), strength,
                       edge_key(c[0].lo, c[0].hi), edge_key(c[1].lo, c[1].hi)});
    }
    return out;
}

}  // namespace

PelGeometry pel_geometry(const TriangleMesh& mesh) {
    PelGeometry g;
    g.grad_basis.resize(mesh.triangles.size() * 3);
    g.corner_weight.resize(mesh.triangles.size() * 3);
    g.vertex_weight.assign(mesh.positions.size(), 0.0f);
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        const glm::vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
        glm::vec3 cr = glm::cross(p[1] - p[0], p[2] - p[0]);
        float twice_area = glm::length(cr);
        if (twice_area <= 0.0f) continue;  // degenerate: no gradient, no weight
        glm::vec3 n = cr / twice_area;
        glm::vec3 w = mixed_areas(p, 0.5f * twice_area);
        for (int i = 0; i < 3; ++i) {
            g.grad_basis[3 * f + i] = glm::cross(n, p[(i + 2) % 3] - p[(i + 1) % 3]) / twice_area;
            g.corner_weight[3 * f + i] = w[i];
            g.vertex_weight[t[i]] += w[i];
        }
    }
    return g;
}

std::vector<glm::vec3> vertex_gradient(const TriangleMesh& mesh, const PelGeometry& geom,
                                       const std::vector<glm::vec3>& normals,
                                       const std::vector<float>& f) {
    std::vector<glm::vec3> grad(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const glm::uvec3& t = mesh.triangles[k];
        glm::vec3 gf = f[t.x] * geom.grad_basis[3 * k] + f[t.y] * geom.grad_basis[3 * k + 1] +
                       f[t.z] * geom.grad_basis[3 * k + 2];
        for (int i = 0; i < 3; ++i) grad[t[i]] += geom.corner_weight[3 * k + i] * gf;
    }
    for (std::size_t i = 0; i < grad.size(); ++i) {
        if (geom.vertex_weight[i] <= 0.0f) continue;
        glm::vec3 g = grad[i] / geom.vertex_weight[i];
        grad[i] = g - glm::dot(g, normals[i]) * normals[i];
    }
    return grad;
}

PelResult photic_extremum_lines(const TriangleMesh& mesh, const PelGeometry& geom,
                                const std::vector<glm::vec3>& normals, const glm::vec3& eye,
                                const PelOptions& options) {
    PelResult r;
    PelField& f = r.field;
    auto start = Clock::now(), t0 = start;
    illumination(mesh, normals, eye, options, f.phi);
    r.timings.illumination = lap_ms(t0);
    std::vector<glm::vec3> grad = vertex_gradient(mesh, geom, normals, f.phi);
    r.timings.gradient = lap_ms(t0);
    normalise_gradient(grad, f);
    r.timings.magnitude = lap_ms(t0);
    f.dw = directional(vertex_gradient(mesh, geom, normals, f.g), f.w);
    r.timings.derivative1 = lap_ms(t0);
    f.dw2 = directional(vertex_gradient(mesh, geom, normals, f.dw), f.w);
    r.timings.derivative2 = lap_ms(t0);
    r.segments = extract_pels(mesh, f, options.threshold);
    r.timings.extraction = lap_ms(t0);
    r.timings.total = ms_since(start);
    return r;
}

std::vector<ObjectSegment> mesh_silhouettes(const TriangleMesh& mesh,
                                            const std::vector<glm::vec3>& normals,
                                            const glm::vec3& eye) {
    std::vector<float> s(mesh.positions.size());
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = glm::dot(normals[i], eye - mesh.positions[i]);
    std::vector<ObjectSegment> out;
    Crossing c[2];
    for (const glm::uvec3& t : mesh.triangles) {
        if (!triangle_crossings(t, s, c)) continue;
        out.push_back({lerp_at(mesh.positions, c[0]), lerp_at(mesh.positions, c[1]), 1.0f,
                       edge_key(c[0].lo, c[0].hi), edge_key(c[1].lo, c[1].hi)});
    }
    return out;
}

namespace {

// Identity of a segment end: its edge key, or its exact coordinates when it has none.
using EndKey = std::tuple<std::uint64_t, float, float, float>;

EndKey end_key(const ObjectSegment& s, int end) {
    std::uint64_t e = end == 0 ? s.edge_a : s.edge_b;
    const glm::vec3& p = end == 0 ? s.a : s.b;
    if (e != ~std::uint64_t(0)) return {e, 0.0f, 0.0f, 0.0f};
    return {e, p.x, p.y, p.z};
}

using EndMap = std::map<EndKey, std::vector<std::pair<std::size_t, int>>>;

// Follows unvisited segments from `key`, pushing their far points via `push`.
template <class Push>
void walk(const std::vector<ObjectSegment>& segs, const EndMap& ends, EndKey key,
          std::vector<char>& used, float& sum, std::size_t& count, Push push) {
    for (;;) {
        auto it = ends.find(key);
        if (it == ends.end()) return;
        bool moved = false;
        for (auto [si, end] : it->second) {
            if (used[si]) continue;
            used[si] = 1;
            sum += segs[si].strength;
            ++count;
            push(end == 0 ? segs[si].b : segs[si].a);
            key = end_key(segs[si], 1 - end);
            moved = true;
            break;
        }
        if (!moved) return;
    }
}

}  // namespace

std::vector<ObjectPolyline> chain_segments(const std::vector<ObjectSegment>& segments,
                                           const std::string& kind) {
    EndMap ends;
    for (std::size_t i = 0; i < segments.size(); ++i)
        for (int e = 0; e < 2; ++e) ends[end_key(segments[i], e)].push_back({i, e});
    std::vector<char> used(segments.size(), 0);
    std::vector<ObjectPolyline> out;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        if (used[i]) continue;
        used[i] = 1;
        float sum = segments[i].strength;
        std::size_t count = 1;
        std::deque<glm::vec3> pts{segments[i].a, segments[i].b};
        walk(segments, ends, end_key(segments[i], 1), used, sum, count,
             [&](const glm::vec3& p) { pts.push_back(p); });
        walk(segments, ends, end_key(segments[i], 0), used, sum, count,
             [&](const glm::vec3& p) { pts.push_front(p); });
        ObjectPolyline pl;
        pl.points.assign(pts.begin(), pts.end());
        pl.strength = sum / float(count);
        pl.kind = kind;
        out.push_back(std::move(pl));
    }
    return out;
}

std::vector<ObjectSegment> curved_only(std::vector<ObjectSegment> segs, const std::vector<glm::vec3>& n) {
    std::erase_if(segs, [&](const ObjectSegment& s) {
        if (s.edge_a == ~std::uint64_t(0) || s.edge_b == ~std::uint64_t(0)) return false;
        const unsigned v[4] = {unsigned(s.edge_a >> 32), unsigned(s.edge_a), unsigned(s.edge_b >> 32), unsigned(s.edge_b)};
        float spread = 0.0f;
        for (int i = 1; i < 4; ++i) spread = std::max(spread, glm::length(n[v[i]] - n[v[0]]));
        return spread < 1e-3f;
    });
    return segs;
}

std::vector<float> pel_line_strengths(const std::vector<ObjectSegment>& segments) {
    // Union-find over segments sharing an end (end_key, as chain_segments joins them).
    std::vector<std::size_t> parent(segments.size());
    for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
    const auto root = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::map<EndKey, std::size_t> first;
    for (std::size_t i = 0; i < segments.size(); ++i)
        for (int e = 0; e < 2; ++e) {
            const auto [it, fresh] = first.emplace(end_key(segments[i], e), i);
            if (!fresh) parent[root(i)] = root(it->second);
        }
    std::vector<double> sum(segments.size(), 0.0);
    for (std::size_t i = 0; i < segments.size(); ++i)
        sum[root(i)] += double(segments[i].strength) * glm::length(segments[i].b - segments[i].a);
    std::vector<float> out(segments.size());
    for (std::size_t i = 0; i < segments.size(); ++i) out[i] = float(sum[root(i)]);
    return out;
}

std::vector<ObjectSegment> strong_pel_lines(const std::vector<ObjectSegment>& segments, float min_strength) {
    if (!(min_strength > 0.0f)) return segments;
    const std::vector<float> strength = pel_line_strengths(segments);
    std::vector<ObjectSegment> out;
    for (std::size_t i = 0; i < segments.size(); ++i)
        if (strength[i] >= min_strength) out.push_back(segments[i]);
    return out;
}

}  // namespace penink
