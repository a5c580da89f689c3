// Stroke weights by flow and by the depth gap behind silhouettes (stroke_weight.hpp).
#include "lines/stroke_weight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace penink {

float log_flow(float flow) { return std::log10(std::max(flow, 1e-12f)); }

void equalise_weights(std::vector<Stroke>& strokes) {
    struct Sample {
        float weight;
        double length;
    };
    std::vector<Sample> samples;
    for (const Stroke& s : strokes) {
        if (s.weight.size() != s.points.size()) continue;
        for (std::size_t i = 0; i < s.points.size(); ++i) {
            double len = 0.0;
            if (i > 0) len += 0.5 * double(glm::length(s.points[i] - s.points[i - 1]));
            if (i + 1 < s.points.size()) len += 0.5 * double(glm::length(s.points[i + 1] - s.points[i]));
            samples.push_back({s.weight[i], len});
        }
    }
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.weight < b.weight; });
    // the cumulative share at the top of each step of equal weights
    std::vector<float> steps;
    std::vector<double> share;
    double total = 0.0;
    for (const Sample& s : samples) total += s.length;
    if (!(total > 0.0)) return;
    double acc = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        acc += samples[i].length;
        if (i + 1 == samples.size() || samples[i + 1].weight != samples[i].weight)
            steps.push_back(samples[i].weight), share.push_back(acc / total);
    }
    for (Stroke& s : strokes) {
        if (s.weight.size() != s.points.size()) continue;
        for (float& w : s.weight) {
            const std::size_t k = std::size_t(std::lower_bound(steps.begin(), steps.end(), w) - steps.begin());
            w = float(std::clamp(share[std::min(k, share.size() - 1)], 0.0, 1.0));
        }
    }
}

std::vector<float> ridge_heights(const VertexLines& lines) {
    const std::size_t n = lines.positions.size();
    const auto on_surface = [&](std::size_t i) {
        return i < lines.normals.size() && (lines.normals[i].x != 0.0f || lines.normals[i].y != 0.0f || lines.normals[i].z != 0.0f);
    };
    float lo = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < n; ++i)
        if (on_surface(i)) lo = std::min(lo, lines.positions[i].z);
    std::vector<float> out(n, std::isfinite(lo) ? lo : 0.0f);
    for (std::size_t i = 0; i < n; ++i)
        if (on_surface(i)) out[i] = lines.positions[i].z;
    return out;
}

float gap_weight(float gap, float gap_half) {
    if (!(gap > 0.0f)) return 0.0f;
    if (!std::isfinite(gap)) return 1.0f;
    return gap / (gap + gap_half);
}

float depth_gap_at(const DepthImage& toward, glm::vec2 p, int radius) {
    const int cx = int(std::floor(p.x)), cy = int(std::floor(p.y));
    float near = std::numeric_limits<float>::infinity(), far = 0.0f;
    bool empty = false;
    for (int y = cy - radius; y <= cy + radius; ++y)
        for (int x = cx - radius; x <= cx + radius; ++x) {
            if (x < 0 || y < 0 || x >= toward.width || y >= toward.height) continue;  // beyond the frame: unknown
            const float d = toward.depth[std::size_t(y) * std::size_t(toward.width) + std::size_t(x)];
            if (!std::isfinite(d)) {
                empty = true;
                continue;
            }
            near = std::min(near, d), far = std::max(far, d);
        }
    if (!std::isfinite(near) || near <= 0.0f) return 0.0f;
    if (empty) return std::numeric_limits<float>::infinity();
    return (far - near) / near;
}

void smooth_along(const std::vector<glm::vec2>& points, std::vector<float>& values, float half_px) {
    const std::size_t n = std::min(points.size(), values.size());
    if (n < 3 || !(half_px > 0.0f)) return;
    std::vector<double> arc(n, 0.0);
    for (std::size_t i = 1; i < n; ++i) arc[i] = arc[i - 1] + glm::length(points[i] - points[i - 1]);
    std::vector<double> prefix(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + values[i];
    std::vector<float> out(n);
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 0; i < n; ++i) {  // points within half_px of arc length: [lo, hi)
        while (arc[i] - arc[lo] > half_px) ++lo;
        hi = std::max(hi, i + 1);
        while (hi < n && arc[hi] - arc[i] <= half_px) ++hi;
        out[i] = float((prefix[hi] - prefix[lo]) / double(hi - lo));
    }
    for (std::size_t i = 0; i < n; ++i) values[i] = out[i];
}

void weigh_by_depth_gap(std::vector<Stroke>& strokes, const DepthImage& toward, const DepthGapParams& params) {
    if (toward.width <= 0 || toward.height <= 0) return;
    for (Stroke& s : strokes) {
        s.weight.resize(s.points.size());
        for (std::size_t i = 0; i < s.points.size(); ++i)
            s.weight[i] = gap_weight(depth_gap_at(toward, s.points[i], params.radius), params.gap_half);
        smooth_along(s.points, s.weight, params.smooth_px);
    }
}

}  // namespace penink
