#include "lines/stroke_directions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

constexpr double deg = 180.0 / std::numbers::pi;

// Angle of direction (dx, dy) to the nearest multiple of 45 degrees, degrees in [0, 22.5].
double off_grid_deg(double dx, double dy) {
    const double a = std::fmod(std::atan2(std::abs(dy), std::abs(dx)) * deg, 45.0);
    return std::min(a, 45.0 - a);
}

// Angle between the axes of unit d and unit a (0-90 degrees).
double axis_angle_deg(glm::dvec2 d, glm::dvec2 a) { return std::acos(std::min(1.0, std::abs(d.x * a.x + d.y * a.y))) * deg; }

// Length-weighted quantile q of (value, weight) pairs.
double weighted_quantile(std::vector<std::pair<double, double>>& v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    double total = 0.0;
    for (const auto& [a, w] : v) total += w;
    double acc = 0.0;
    for (const auto& [a, w] : v) {
        acc += w;
        if (acc >= q * total) return a;
    }
    return v.back().first;
}

}  // namespace

FallLineField::FallLineField(Terrain terrain)
    : terrain_(std::move(terrain)), surface_(terrain_), grad_(terrain_.size(), glm::vec2(0.0f)) {
    const Terrain& t = terrain_;
    const int nc = t.cols, nr = t.rows;
    auto ok = [&](int c, int r) { return c >= 0 && r >= 0 && c < nc && r < nr && t.valid[t.index(c, r)]; };
    parallel_chunks(std::size_t(nr), 64, [&](std::size_t r0, std::size_t r1) {
        for (int r = int(r0); r < int(r1); ++r)
            for (int c = 0; c < nc; ++c) {
                if (!ok(c, r)) continue;
                // differences along the columns and rows, central where both neighbours hold data
                auto diff = [&](int dc, int dr, glm::dvec3& d) {
                    const bool fwd = ok(c + dc, r + dr), back = ok(c - dc, r - dr);
                    if (!fwd && !back) return false;
                    const glm::vec3 a = t.pos[t.index(fwd ? c + dc : c, fwd ? r + dr : r)];
                    const glm::vec3 b = t.pos[t.index(back ? c - dc : c, back ? r - dr : r)];
                    d = glm::dvec3(a) - glm::dvec3(b);
                    return true;
                };
                glm::dvec3 u, v;
                if (!diff(1, 0, u) || !diff(0, 1, v)) continue;
                // [u.x u.y; v.x v.y] (gx, gy) = (u.z, v.z)
                const double det = u.x * v.y - u.y * v.x;
                if (std::abs(det) < 1e-30) continue;
                grad_[t.index(c, r)] = glm::vec2(float((u.z * v.y - u.y * v.z) / det), float((u.x * v.z - u.z * v.x) / det));
            }
    });
}

bool FallLineField::sample(double x, double y, Sample& s, int& c, int& r) const {
    const DemDraper draper(surface_);
    DemHit hit;
    if (!draper.locate(x, y, c, r, hit)) return false;
    s.gradient = glm::dvec2(0.0);
    for (int k = 0; k < 3; ++k) s.gradient += double(hit.bary[k]) * glm::dvec2(grad_[hit.node[k]]);
    const int cc = int(hit.cell % std::uint32_t(surface_.cols() - 1)), cr = int(hit.cell / std::uint32_t(surface_.cols() - 1));
    const glm::dvec2 o(surface_.node_xy(cc, cr));
    const glm::dvec2 u = glm::dvec2(surface_.node_xy(cc + 1, cr)) - o, v = glm::dvec2(surface_.node_xy(cc, cr + 1)) - o;
    const glm::dvec2 axes[4] = {u, v, u + v, u - v};
    for (int k = 0; k < 4; ++k) s.axes[k] = axes[k] / std::max(1e-30, std::hypot(axes[k].x, axes[k].y));
    return true;
}

StrokeDirections stroke_directions(const std::vector<std::vector<glm::dvec2>>& lines, const FallLineField& field,
                                   double min_slope_deg, double grid_tolerance_deg) {
    StrokeDirections out;
    const double min_grad = std::tan(min_slope_deg / deg);
    std::vector<std::pair<double, double>> angles;  // (angle to the fall line, length)
    for (const auto& line : lines) {
        int c = -1, r = -1;
        for (std::size_t k = 1; k < line.size(); ++k) {
            const glm::dvec2 d = line[k] - line[k - 1];
            const double len = std::hypot(d.x, d.y);
            if (!(len > 1e-9)) continue;
            out.length += len;
            const glm::dvec2 m = 0.5 * (line[k] + line[k - 1]);
            FallLineField::Sample s;
            if (!field.sample(m.x, m.y, s, c, r)) {
                if (off_grid_deg(d.x, d.y) <= grid_tolerance_deg) out.grid_length += len;
                c = r = -1;
                continue;
            }
            const glm::dvec2 u = d / len;
            double off = 90.0;
            for (const glm::dvec2& a : s.axes) off = std::min(off, axis_angle_deg(u, a));
            if (off <= grid_tolerance_deg) out.grid_length += len;
            const double gl = std::hypot(s.gradient.x, s.gradient.y);
            if (!(gl > min_grad)) continue;
            angles.emplace_back(axis_angle_deg(u, s.gradient / gl), len);
            ++out.sloped_segments, out.sloped_length += len;
        }
    }
    out.fall_median_deg = weighted_quantile(angles, 0.5);
    out.fall_p90_deg = weighted_quantile(angles, 0.9);
    return out;
}

}  // namespace penink
