#include "core/polyline_simplify.hpp"

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

// Values along a polyline and the arc length at each point, for dp_range.
struct ValueProfile {
    const std::vector<float>* value = nullptr;
    std::vector<double> arc;
};

// Marks the kept points of pts[first..last] (both ends already kept). With values, a point's
// error is the larger of its distance and tol x its value's distance from the chord's (linear in
// arc length) / value_tol.
void dp_range(const std::vector<glm::vec2>& pts, std::size_t first, std::size_t last, float tol,
              std::vector<char>& keep, const ValueProfile* profile = nullptr, float value_tol = 1.0f) {
    std::vector<std::pair<std::size_t, std::size_t>> stack{{first, last}};
    while (!stack.empty()) {
        auto [a, b] = stack.back();
        stack.pop_back();
        float worst = -1.0f;
        std::size_t at = a;
        for (std::size_t i = a + 1; i < b; ++i) {
            float d = point_segment_distance(pts[i], pts[a], pts[b]);
            if (profile) {
                const std::vector<float>& w = *profile->value;
                const double span = profile->arc[b] - profile->arc[a];
                const float f = span > 0.0 ? float((profile->arc[i] - profile->arc[a]) / span) : 0.0f;
                const float chord = w[a] + f * (w[b] - w[a]);
                d = std::max(d, tol * std::abs(w[i] - chord) / value_tol);
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
    out.reserve(std::size_t(std::count(keep.begin(), keep.end(), char(1))));
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

std::vector<std::size_t> douglas_peucker_indices(const std::vector<glm::vec2>& pts, float tol,
                                                 const std::vector<float>& values, float value_tol) {
    if (pts.empty()) return {};
    ValueProfile profile{&values, std::vector<double>(pts.size(), 0.0)};
    for (std::size_t i = 1; i < pts.size(); ++i) profile.arc[i] = profile.arc[i - 1] + double(glm::length(pts[i] - pts[i - 1]));
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    dp_range(pts, 0, pts.size() - 1, tol, keep, &profile, value_tol);
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
    if (std::count(keep.begin(), keep.end(), char(1)) < 3) {  // collapsed to a segment: keep the point farthest from it
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

}  // namespace penink
