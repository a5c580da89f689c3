#include "lines/line_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "lines/simplify.hpp"
#include "lines/stroke_point_grid.hpp"

namespace penink {

double stroke_length(const Stroke& s) {
    double l = 0.0;
    for (std::size_t i = 1; i < s.points.size(); ++i) {
        const glm::vec2 d = s.points[i] - s.points[i - 1];
        l += std::sqrt(double(d.x) * d.x + double(d.y) * d.y);
    }
    return l;
}

float stroke_extent(const Stroke& s) {
    if (s.points.empty()) return 0.0f;
    glm::vec2 lo = s.points[0], hi = s.points[0];
    for (const glm::vec2& p : s.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return std::max(hi.x - lo.x, hi.y - lo.y);
}

LineMetrics line_metrics(const std::vector<Stroke>& strokes, float loop_px, float near_px, float min_run_px) {
    LineMetrics m;
    struct Sample {
        glm::vec2 p;
        std::uint32_t stroke;
        float length;  // of the stretch it stands for
    };
    std::vector<Sample> samples;
    constexpr float step = 0.25f;
    for (std::size_t k = 0; k < strokes.size(); ++k) {
        const Stroke& s = strokes[k];
        if (s.points.empty()) continue;
        ++m.paths;
        if (is_closed(s) && stroke_extent(s) < loop_px) ++m.small_loops;
        for (std::size_t i = 1; i < s.points.size(); ++i) {
            const glm::vec2 a = s.points[i - 1], b = s.points[i];
            const float len = glm::length(b - a);
            const int n = std::max(1, int(std::ceil(len / step)));
            for (int j = 0; j < n; ++j)
                samples.push_back({a + (b - a) * ((float(j) + 0.5f) / float(n)), std::uint32_t(k), len / float(n)});
            m.length += len;
        }
    }
    StrokePointGrid grid(std::max(near_px, 1e-3f));
    for (const Sample& s : samples) grid.add(s.p, int(s.stroke));
    std::vector<char> near(samples.size(), 0);
    for (std::size_t i = 0; i < samples.size(); ++i) near[i] = grid.near_other(samples[i].p, int(samples[i].stroke), near_px);
    // Runs of near samples along one stroke at least min_run_px long: a crossing or a junction
    // touches another stroke over a pixel or two, a doubled line runs beside it.
    for (std::size_t i = 0; i < samples.size();) {
        std::size_t j = i;
        double run = 0.0;
        while (j < samples.size() && near[j] && samples[j].stroke == samples[i].stroke) run += samples[j].length, ++j;
        if (j == i) {
            ++i;
            continue;
        }
        if (run >= min_run_px) m.doubled_length += run;
        i = j;
    }
    return m;
}

}  // namespace penink
