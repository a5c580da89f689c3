#include "lines/simplify.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace penink {

namespace {

Stroke without_duplicates(const Stroke& s) {
    Stroke out;
    out.strength = s.strength;
    out.kind = s.kind;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (!out.points.empty() && out.points.back() == s.points[i]) continue;
        out.points.push_back(s.points[i]);
        out.depth.push_back(i < s.depth.size() ? s.depth[i] : 0.0f);
        if (!s.weight.empty()) out.weight.push_back(weight_at(s, i));
    }
    return out;
}

Stroke pick(const Stroke& s, const std::vector<std::size_t>& idx, bool close) {
    Stroke out;
    out.strength = s.strength;
    out.kind = s.kind;
    for (std::size_t i : idx) {
        out.points.push_back(s.points[i]);
        out.depth.push_back(s.depth[i]);
        if (!s.weight.empty()) out.weight.push_back(weight_at(s, i));
    }
    if (close && !out.points.empty()) {
        out.points.push_back(out.points.front());
        out.depth.push_back(out.depth.front());
        if (!out.weight.empty()) out.weight.push_back(out.weight.front());
    }
    return out;
}

}  // namespace

Stroke simplify_stroke(const Stroke& s, float tol) {
    Stroke clean = without_duplicates(s);
    if (tol <= 0.0f || clean.points.size() < 3) return clean;
    if (is_closed(clean)) {
        std::vector<glm::vec2> ring(clean.points.begin(), clean.points.end() - 1);
        return pick(clean, douglas_peucker_ring_indices(ring, tol), true);
    }
    if (clean.weight.size() == clean.points.size())  // the width along the stroke kept too
        return pick(clean, douglas_peucker_indices(clean.points, tol, clean.weight, kWeightTolerance), false);
    return pick(clean, douglas_peucker_indices(clean.points, tol), false);
}

std::vector<Stroke> simplify_strokes(const std::vector<Stroke>& strokes, float tol) {
    std::vector<Stroke> out;
    out.reserve(strokes.size());
    for (const Stroke& s : strokes) out.push_back(simplify_stroke(s, tol));
    return out;
}

Ring simplify_ring(const Ring& ring, float tol) {
    if (ring.size() < 4) return ring;
    Ring out;
    for (std::size_t i : douglas_peucker_ring_indices(ring, tol)) out.push_back(ring[i]);
    return out;
}

Ring remove_collinear(const Ring& ring, float eps) {
    std::size_t n = ring.size();
    if (n < 4) return ring;
    Ring out;
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec2 a = ring[(i + n - 1) % n], p = ring[i], b = ring[(i + 1) % n];
        glm::vec2 ab = b - a, ap = p - a;
        float cross = ab.x * ap.y - ab.y * ap.x;
        float len = glm::length(ab);
        bool between = glm::dot(ap, ab) >= 0.0f && glm::dot(p - b, a - b) >= 0.0f;
        if (len > 0.0f && std::fabs(cross) / len <= eps && between) continue;
        out.push_back(p);
    }
    return out.size() >= 3 ? out : ring;
}

}  // namespace penink
