// Variable-width stroke outlines (stroke_outline.hpp).
#include "export/stroke_outline.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/polyline_simplify.hpp"

namespace penink {

namespace {

glm::vec2 perp(glm::vec2 d) { return {-d.y, d.x}; }

glm::vec2 rotated(glm::vec2 v, double a) {
    const double c = std::cos(a), s = std::sin(a);
    return {float(v.x * c - v.y * s), float(v.x * s + v.y * c)};
}

constexpr double tolerance_px = 0.05;  // the polygon's largest distance from the true round outline
constexpr float thin_px = 0.05f;       // Douglas-Peucker tolerance of the polygon's points

// Points of the arc of radius r about c from direction `from` through `sweep` radians, the
// first point left out, the last included; chords within tolerance_px of the arc (at most 90
// degrees each).
void arc(std::vector<glm::vec2>& out, glm::vec2 c, double r, glm::vec2 from, double sweep) {
    if (r <= 1e-4) {
        out.push_back(c);
        return;
    }
    const double step = r > tolerance_px ? std::min(M_PI / 2.0, 2.0 * std::acos(1.0 - tolerance_px / r)) : M_PI / 2.0;
    const int n = std::max(1, int(std::ceil(std::abs(sweep) / step)));
    for (int k = 1; k <= n; ++k) out.push_back(c + rotated(from, sweep * k / n) * float(r));
}

// One side (s = +1 left, -1 right) of the stroke at interior point i, walking forward (s = +1)
// or backward (s = -1).
void side_join(std::vector<glm::vec2>& out, glm::vec2 p, double r, glm::vec2 d0, glm::vec2 d1, float s) {
    const glm::vec2 n0 = perp(d0) * s, n1 = perp(d1) * s;
    const float cross = d0.x * d1.y - d0.y * d1.x, dot = glm::dot(d0, d1);
    glm::vec2 m = n0 + n1;
    const float ml = glm::length(m);
    // a mitre where it stays within tolerance_px of the round join: r (1 / cos(a / 2) - 1), a the
    // turn (cos(a / 2) = |m| / 2), and always under 10 degrees
    const double half_cos = 0.5 * double(ml);
    if (ml > 1e-6f && (dot > 0.985f || (half_cos > 0.7 && r * (1.0 / half_cos - 1.0) <= tolerance_px))) {
        m /= ml;
        out.push_back(p + m * float(r / std::max(double(glm::dot(m, n0)), 0.5)));
        return;
    }
    const bool outer = s * cross < 0.0f;
    if (outer) {
        const glm::vec2 a = s > 0 ? n0 : n1, b = s > 0 ? n1 : n0;  // in walking order
        out.push_back(p + a * float(r));
        arc(out, p, r, a, std::atan2(a.x * b.y - a.y * b.x, glm::dot(a, b)));
        return;
    }
    if (ml < 1e-6f) {  // a hairpin: the inner side meets at the point
        out.push_back(p);
        return;
    }
    m /= ml;
    out.push_back(p + m * float(r / std::max(double(glm::dot(m, n0)), 0.5)));
}

}  // namespace

std::vector<glm::vec2> stroke_outline(const std::vector<glm::vec2>& points, const std::vector<double>& widths) {
    std::vector<glm::vec2> p;
    std::vector<double> r;
    for (std::size_t i = 0; i < points.size() && i < widths.size(); ++i) {
        if (!p.empty() && p.back() == points[i]) {
            r.back() = std::max(r.back(), 0.5 * widths[i]);
            continue;
        }
        p.push_back(points[i]);
        r.push_back(0.5 * std::max(widths[i], 0.0));
    }
    std::vector<glm::vec2> out;
    if (p.empty()) return out;
    if (p.size() == 1) {  // a dot
        arc(out, p[0], r[0], {1.0f, 0.0f}, 2.0 * M_PI);
        out.pop_back();
        return out;
    }
    const std::size_t n = p.size();
    std::vector<glm::vec2> d(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) d[i] = glm::normalize(p[i + 1] - p[i]);
    out.reserve(4 * n + 16);
    out.push_back(p[0] + perp(d[0]) * float(r[0]));
    for (std::size_t i = 1; i + 1 < n; ++i) side_join(out, p[i], r[i], d[i - 1], d[i], 1.0f);
    out.push_back(p[n - 1] + perp(d[n - 2]) * float(r[n - 1]));
    arc(out, p[n - 1], r[n - 1], perp(d[n - 2]), -M_PI);
    for (std::size_t i = n - 2; i >= 1; --i) side_join(out, p[i], r[i], d[i - 1], d[i], -1.0f);
    out.push_back(p[0] - perp(d[0]) * float(r[0]));
    arc(out, p[0], r[0], -perp(d[0]), -M_PI);
    out.pop_back();  // the first point again
    std::vector<glm::vec2> kept;
    kept.reserve(out.size());
    for (std::size_t i : douglas_peucker_ring_indices(out, thin_px)) kept.push_back(out[i]);
    return kept;
}

}  // namespace penink
