#include "lines/sketchy.hpp"

#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "lines/random_bits.hpp"
#include "lines/simplify.hpp"

namespace penink {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// Uniform point in the disc of radius r from draws k, k+1.
glm::vec2 disc_offset(float r, std::uint64_t seed, std::uint64_t id, std::uint64_t k) {
    double radius = r * std::sqrt(random_unit(seed, id, k));
    double angle = kTwoPi * random_unit(seed, id, k + 1);
    return {float(radius * std::cos(angle)), float(radius * std::sin(angle))};
}

std::vector<float> arc_lengths(const std::vector<glm::vec2>& pts) {
    std::vector<float> s(pts.size(), 0.0f);
    for (std::size_t i = 1; i < pts.size(); ++i) s[i] = s[i - 1] + glm::length(pts[i] - pts[i - 1]);
    return s;
}

// Moves the end point at index `end` outward by d along the tangent towards it from the first
// point at least 1 px away.
void extend_end(std::vector<glm::vec2>& pts, bool at_start, float d) {
    const std::size_t n = pts.size();
    glm::vec2 e = at_start ? pts.front() : pts.back();
    for (std::size_t k = 1; k < n; ++k) {
        glm::vec2 q = at_start ? pts[k] : pts[n - 1 - k];
        float l = glm::length(e - q);
        if (l >= 1.0f || k == n - 1) {
            if (l <= 0.0f) return;
            (at_start ? pts.front() : pts.back()) = e + (e - q) * (d / l);
            return;
        }
    }
}

}  // namespace

Stroke sketch_stroke(const Stroke& s, const SketchParams& p, std::uint64_t seed, std::uint64_t stroke_id,
                     int pass) {
    Stroke out = s;
    if (out.points.empty()) return out;
    const bool closed = is_closed(s);
    if (!closed && p.overshoot > 0.0f && out.points.size() >= 2) {
        extend_end(out.points, true, p.overshoot);
        extend_end(out.points, false, p.overshoot);
    }
    const std::uint64_t k0 = std::uint64_t(pass) * 16;
    const glm::vec2 a = disc_offset(p.amount, seed, stroke_id, k0);
    const glm::vec2 b = closed ? a : disc_offset(p.amount, seed, stroke_id, k0 + 2);
    const std::vector<glm::vec2> base = out.points;
    const std::vector<float> arc = arc_lengths(base);
    const float total = arc.back();
    const std::size_t n = base.size();
    for (std::size_t i = 0; i < n; ++i) {
        float t = total > 0.0f ? arc[i] / total : 0.0f;
        const glm::vec2 off = i == n - 1 ? b : a + (b - a) * t;
        out.points[i] = base[i] + off;
    }
    return out;
}

std::vector<Stroke> sketch_copies(const Stroke& s, const SketchParams& p, std::uint64_t seed,
                                  std::uint64_t stroke_id) {
    std::vector<Stroke> out;
    for (int pass = 0; pass <= std::max(p.repeat, 0); ++pass) out.push_back(sketch_stroke(s, p, seed, stroke_id, pass));
    return out;
}

std::uint64_t stroke_geometry_id(const Stroke& s) {
    const auto bits = float_bits;
    std::uint64_t h = splitmix64(s.points.size());
    if (!s.points.empty()) {
        h = splitmix64(h ^ (bits(s.points.front().x) << 32 | bits(s.points.front().y)));
        h = splitmix64(h ^ (bits(s.points.back().x) << 32 | bits(s.points.back().y)));
    }
    for (unsigned char c : s.kind) h = splitmix64(h ^ c);
    return h;
}

namespace {

// Orthonormal tangent basis of unit normal n (Duff et al., JCGT 6(1), 2017).
void tangent_basis(glm::vec3 n, glm::vec3& t1, glm::vec3& t2) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    t1 = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t2 = {b, sign + n.y * n.y * a, -n.y};
}

glm::vec3 project_to_plane(glm::vec3 v, glm::vec3 n) {
    float l = glm::length(n);
    if (!(l > 1e-12f)) return glm::vec3(0.0f);
    n /= l;
    return v - n * glm::dot(n, v);
}

glm::vec3 end_offset(glm::vec3 normal, float amount, std::uint64_t seed, std::uint64_t id, std::uint64_t k) {
    float l = glm::length(normal);
    if (!(l > 1e-12f)) return glm::vec3(0.0f);
    glm::vec3 t1, t2;
    tangent_basis(normal / l, t1, t2);
    glm::vec2 d = disc_offset(amount, seed, id, k);
    return project_to_plane(t1 * d.x + t2 * d.y, normal);
}

}  // namespace

std::vector<glm::vec3> sketch_polyline_3d(const std::vector<glm::vec3>& points,
                                          const std::vector<glm::vec3>& normals, float amount,
                                          std::uint64_t seed, std::uint64_t id) {
    if (normals.size() != points.size())
        throw Error("lines", "",
                    "sketch_polyline_3d: " + std::to_string(points.size()) + " points but " +
                        std::to_string(normals.size()) + " normals",
                    ExitCode::internal);
    std::vector<glm::vec3> out = points;
    if (points.empty()) return out;
    const glm::vec3 a = end_offset(normals.front(), amount, seed, id, 0);
    const glm::vec3 b = end_offset(normals.back(), amount, seed, id, 2);
    std::vector<float> arc(points.size(), 0.0f);
    for (std::size_t i = 1; i < points.size(); ++i) arc[i] = arc[i - 1] + glm::length(points[i] - points[i - 1]);
    for (std::size_t i = 0; i < points.size(); ++i) {
        float t = arc.back() > 0.0f ? arc[i] / arc.back() : 0.0f;
        glm::vec3 off = i == 0 ? a : i + 1 == points.size() ? b : project_to_plane(a + (b - a) * t, normals[i]);
        out[i] = points[i] + off;
    }
    return out;
}

}  // namespace penink
