#include "lines/simplify.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace penink {

float point_segment_distance(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
    glm::vec2 ab = b - a;
    float len2 = glm::dot(ab, ab);
    if (len2 <= 0.0f) return glm::length(p - a);
    float t = std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}


namespace {

// A stroke's weights and the arc length at each point, for dp_range.
struct WeightProfile {
    const std::vector<float>* weight = nullptr;
    std::vector<double> arc;
};

// Marks the kept points of pts[first..last] (both ends already kept). With weights, a point's
// error is the larger of its distance and tol x its weight's distance from the chord's (linear in
// arc length, as the writers draw it) / weight_tol.
void dp_range(const std::vector<glm::vec2>& pts, std::size_t first, std::size_t last, float tol,
              std::vector<char>& keep, const WeightProfile* profile = nullptr, float weight_tol = 1.0f) {
    std::vector<std::pair<std::size_t, std::size_t>> stack{{first, last}};
    while (!stack.empty()) {
        auto [a, b] = stack.back();
        stack.pop_back();
        float worst = -1.0f;
        std::size_t at = a;
        for (std::size_t i = a + 1; i < b; ++i) {
            float d = point_segment_distance(pts[i], pts[a], pts[b]);
            if (profile) {
                const std::vector<float>& w = *profile->weight;
                const double span = profile->arc[b] - profile->arc[a];
                const float f = span > 0.0 ? float((profile->arc[i] - profile->arc[a]) / span) : 0.0f;
                const float chord = w[a] + f * (w[b] - w[a]);
                d = std::max(d, tol * std::abs(w[i] - chord) / weight_tol);
            }
            if (d > worst) worst = d, at = i;
        }
        if (at == a || worst <= tol) continue;
        keep[at] = 1;
        stack.push_back({at, b});
        stack.push_back({a, at});
    }
}

std::vector<std::size_t> kept(const std::vector<char>& keep) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) out.push_back(i);
    return out;
}

}  // namespace

std::vector<std::size_t> douglas_peucker_indices(const std::vector<glm::vec2>& pts, float tol) {
    if (pts.empty()) return {};
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    dp_range(pts, 0, pts.size() - 1, tol, keep);
    return kept(keep);
}

std::vector<std::size_t> douglas_peucker_ring_indices(const std::vector<glm::vec2>& pts, float tol) {
    std::size_t n = pts.size();
    if (n < 4) return kept(std::vector<char>(n, 1));
    std::size_t far = 0;
    float best = -1.0f;
    for (std::size_t i = 1; i < n; ++i) {
        float d = glm::length(pts[i] - pts[0]);
        if (d > best) best = d, far = i;
    }
    std::vector<glm::vec2> closed(pts);
    closed.push_back(pts[0]);
    std::vector<char> keep(n + 1, 0);
    keep[0] = keep[far] = keep[n] = 1;
    dp_range(closed, 0, far, tol, keep);
    dp_range(closed, far, n, tol, keep);
    keep.pop_back();
    if (kept(keep).size() < 3) {  // collapsed to a segment: keep the point farthest from it
        std::size_t at = 0;
        float worst = -1.0f;
        for (std::size_t i = 1; i < n; ++i) {
            float d = point_segment_distance(pts[i], pts[0], pts[far]);
            if (i != far && d > worst) worst = d, at = i;
        }
        keep[at] = 1;
    }
    return kept(keep);
}

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
    if (clean.weight.size() == clean.points.size()) {  // the width along the stroke kept too
        WeightProfile profile{&clean.weight, std::vector<double>(clean.points.size(), 0.0)};
        for (std::size_t i = 1; i < clean.points.size(); ++i)
            profile.arc[i] = profile.arc[i - 1] + double(glm::length(clean.points[i] - clean.points[i - 1]));
        std::vector<char> keep(clean.points.size(), 0);
        keep.front() = keep.back() = 1;
        dp_range(clean.points, 0, clean.points.size() - 1, tol, keep, &profile, kWeightTolerance);
        return pick(clean, kept(keep), false);
    }
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
