#include "lines/spacing_thinning.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace penink {

namespace {

// Accepted points hashed by cell of size `spacing`: a query looks at the 3x3 cells around.
class PointGrid {
public:
    explicit PointGrid(float spacing) : cell_(spacing), r2_(spacing * spacing) {}
    bool near(glm::vec2 p) const {
        const long cx = cell(p.x), cy = cell(p.y);
        for (long y = cy - 1; y <= cy + 1; ++y)
            for (long x = cx - 1; x <= cx + 1; ++x) {
                const auto it = cells_.find(key(x, y));
                if (it == cells_.end()) continue;
                for (const glm::vec2& q : it->second) {
                    const glm::vec2 d = q - p;
                    if (d.x * d.x + d.y * d.y < r2_) return true;
                }
            }
        return false;
    }
    void add(glm::vec2 p) { cells_[key(cell(p.x), cell(p.y))].push_back(p); }

private:
    long cell(float v) const { return long(std::floor(v / cell_)); }
    static long long key(long x, long y) { return (static_cast<long long>(x) << 32) ^ (y & 0xffffffffLL); }
    float cell_, r2_;
    std::unordered_map<long long, std::vector<glm::vec2>> cells_;
};

// Splits `s` into runs of points not near `grid` (densified to half a spacing so gaps show).
float polyline_length(const std::vector<glm::vec2>& p) {
    float len = 0.0f;
    for (std::size_t i = 1; i < p.size(); ++i) len += glm::length(p[i] - p[i - 1]);
    return len;
}

void accept_runs(const Stroke& s, const PointGrid& grid, float min_length, std::vector<Stroke>& out) {
    Stroke run;
    run.kind = s.kind, run.strength = s.strength;
    auto flush = [&] {
        if (run.points.size() >= 2 && polyline_length(run.points) >= min_length) out.push_back(run);
        run.points.clear(), run.depth.clear(), run.weight.clear();
    };
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (grid.near(s.points[i])) { flush(); continue; }
        run.points.push_back(s.points[i]);
        run.depth.push_back(s.depth[i]);
        if (!s.weight.empty()) run.weight.push_back(weight_at(s, i));
    }
    flush();
}

// Inserts points so no segment is longer than `step` (depth interpolated linearly).
Stroke densify(const Stroke& s, float step) {
    Stroke d;
    d.kind = s.kind, d.strength = s.strength;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (i > 0) {
            const glm::vec2 a = s.points[i - 1], b = s.points[i];
            const int n = int(std::ceil(glm::length(b - a) / step));
            for (int k = 1; k < n; ++k) {
                const float t = float(k) / float(n);
                d.points.push_back(a + (b - a) * t);
                d.depth.push_back(s.depth[i - 1] + (s.depth[i] - s.depth[i - 1]) * t);
                if (!s.weight.empty()) d.weight.push_back(weight_at(s, i - 1) + (weight_at(s, i) - weight_at(s, i - 1)) * t);
            }
        }
        d.points.push_back(s.points[i]);
        d.depth.push_back(s.depth[i]);
        if (!s.weight.empty()) d.weight.push_back(weight_at(s, i));
    }
    return d;
}

}  // namespace

std::vector<Stroke> thin_by_spacing(const std::vector<Stroke>& strokes, float spacing, float min_length) {
    if (spacing <= 0.0f) return strokes;
    if (min_length < 0.0f) min_length = 3.0f * spacing;
    std::vector<std::size_t> order(strokes.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return strokes[a].strength > strokes[b].strength; });
    PointGrid grid(spacing);
    std::vector<Stroke> out;
    for (std::size_t i : order) {
        // a stroke shorter than a piece may be leaves nothing (its pieces lie on it, densified;
        // 1e-5: what summing its segments again may round to, kept)
        if (polyline_length(strokes[i].points) < min_length * (1.0f - 1e-5f)) continue;
        const std::size_t first = out.size();
        accept_runs(densify(strokes[i], spacing * 0.5f), grid, min_length, out);
        // A stroke does not block itself: its points enter the grid only after it is cut.
        for (std::size_t k = first; k < out.size(); ++k)
            for (const glm::vec2& p : out[k].points) grid.add(p);
    }
    return out;
}

}  // namespace penink
