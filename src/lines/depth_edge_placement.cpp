#include "lines/depth_edge_placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penink {

namespace {

// Offset from pixel (x, y)'s centre to the depth edge it borders; (0, 0) when none.
glm::vec2 edge_offset(const DepthImage& toward, const DepthImage& away, int x, int y) {
    const int w = toward.width, h = toward.height;
    const auto at = [&](const DepthImage& img, int u, int v) {
        u = std::clamp(u, 0, w - 1), v = std::clamp(v, 0, h - 1);
        const float d = img.depth[std::size_t(v) * w + u];
        return std::isfinite(d) ? d : std::numeric_limits<float>::infinity();
    };
    const float t = at(toward, x, y);
    if (!std::isfinite(t)) return {0.0f, 0.0f};
    float a = std::numeric_limits<float>::infinity();  // nearest away fragment behind t (as the SIL pass)
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            if (const float q = at(away, x + dx, y + dy); q > t && q < a) a = q;
    if (!std::isfinite(a)) return {0.0f, 0.0f};
    glm::vec2 d(0.0f);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            const bool outside = u < 0 || v < 0 || u >= w || v >= h;
            if ((dx || dy) && !outside && at(toward, u, v) > a) d += glm::vec2(float(dx), float(dy));
        }
    const float m = std::max(std::abs(d.x), std::abs(d.y));
    return m > 0.0f ? d * (0.5f / m) : glm::vec2(0.0f);
}

}  // namespace

void place_on_depth_edges(std::vector<Stroke>& strokes, const DepthImage& toward, const DepthImage& away) {
    if (toward.width <= 0 || toward.height <= 0 || away.width != toward.width || away.height != toward.height) return;
    for (Stroke& s : strokes)
        for (glm::vec2& p : s.points) {
            const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
            if (x < 0 || y < 0 || x >= toward.width || y >= toward.height) continue;
            p += edge_offset(toward, away, x, y);
        }
}

}  // namespace penink
