#include "lines/doubled_lines.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "lines/line_metrics.hpp"
#include "lines/stroke_point_grid.hpp"

namespace penink {

namespace {

// px between samples: as fine as line_metrics' (0.25 px), so a stretch the measure counts as
// doubled is cut here (at 0.5 px a sample's distance to a line sampled beside it overstates the
// line's distance, and runs just over min_run px stayed)
constexpr float kStep = 0.25f;

// Arc length at each point of a stroke.
std::vector<double> arc_lengths(const Stroke& s) {
    std::vector<double> t(s.points.size(), 0.0);
    for (std::size_t i = 1; i < s.points.size(); ++i) t[i] = t[i - 1] + glm::length(s.points[i] - s.points[i - 1]);
    return t;
}

// Point (and depth, and weight) at arc length u of a stroke with arc lengths t.
void point_at(const Stroke& s, const std::vector<double>& t, double u, glm::vec2& p, float& d, float& w) {
    const std::size_t i = std::size_t(std::upper_bound(t.begin(), t.end(), u) - t.begin());
    if (i == 0) return void((p = s.points.front(), d = s.depth.front(), w = weight_at(s, 0)));
    if (i >= t.size()) return void((p = s.points.back(), d = s.depth.back(), w = weight_at(s, t.size() - 1)));
    const double span = t[i] - t[i - 1];
    const float f = span > 0.0 ? float((u - t[i - 1]) / span) : 0.0f;
    p = s.points[i - 1] + (s.points[i] - s.points[i - 1]) * f;
    d = s.depth[i - 1] + (s.depth[i] - s.depth[i - 1]) * f;
    w = weight_at(s, i - 1) + (weight_at(s, i) - weight_at(s, i - 1)) * f;
}

// The part of a stroke between arc lengths a < b.
Stroke sub_stroke(const Stroke& s, const std::vector<double>& t, double a, double b) {
    Stroke out;
    out.strength = s.strength, out.kind = s.kind;
    const bool weighted = !s.weight.empty();
    glm::vec2 p;
    float d, w;
    point_at(s, t, a, p, d, w);
    out.points.push_back(p), out.depth.push_back(d);
    if (weighted) out.weight.push_back(w);
    for (std::size_t i = 0; i < t.size(); ++i)
        if (t[i] > a && t[i] < b) {
            out.points.push_back(s.points[i]), out.depth.push_back(s.depth[i]);
            if (weighted) out.weight.push_back(weight_at(s, i));
        }
    point_at(s, t, b, p, d, w);
    out.points.push_back(p), out.depth.push_back(d);
    if (weighted) out.weight.push_back(w);
    return out;
}

// Samples every kStep along a stroke (both ends included), with their arc lengths.
void samples_of(const Stroke& s, const std::vector<double>& t, std::vector<glm::vec2>& p, std::vector<double>& u) {
    p.clear(), u.clear();
    const double length = t.empty() ? 0.0 : t.back();
    const int n = std::max(1, int(std::ceil(length / kStep)));
    for (int k = 0; k <= n; ++k) {
        const double a = length * double(k) / double(n);
        glm::vec2 q;
        float d, w;
        point_at(s, t, a, q, d, w);
        p.push_back(q), u.push_back(a);
    }
}

}  // namespace

std::vector<Stroke> merge_doubled(std::vector<Stroke> strokes, float width, float min_run,
                                  const std::vector<Stroke>& above) {
    if (!(width > 0.0f)) return strokes;
    for (Stroke& s : strokes)
        if (s.depth.size() != s.points.size()) s.depth.resize(s.points.size(), 0.0f);
    StrokePointGrid grid(std::max(width, 1e-3f));
    std::vector<glm::vec2> p;
    std::vector<double> u;
    for (const Stroke& s : above) {
        if (s.points.size() < 2) continue;
        samples_of(s, arc_lengths(s), p, u);
        for (const glm::vec2& q : p) grid.add(q, -1);
    }
    std::vector<double> length(strokes.size());
    for (std::size_t i = 0; i < strokes.size(); ++i) length[i] = stroke_length(strokes[i]);
    std::vector<std::size_t> order(strokes.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (strokes[a].strength != strokes[b].strength) return strokes[a].strength > strokes[b].strength;
        return length[a] > length[b];
    });
    std::vector<std::vector<Stroke>> kept(strokes.size());
    for (const std::size_t i : order) {
        const Stroke& s = strokes[i];
        if (s.points.size() < 2) {
            kept[i].push_back(s);
            continue;
        }
        const std::vector<double> t = arc_lengths(s);
        samples_of(s, t, p, u);
        std::vector<char> near(p.size(), 0), cut(p.size(), 0);
        for (std::size_t k = 0; k < p.size(); ++k) near[k] = grid.near_other(p[k], int(i), width);
        // A stroke zigzagging about an accepted one leaves its band for a pixel or so at a time:
        // gaps under 2 widths between near stretches count as near (else each stretch is short,
        // none is cut, and the accepted stroke runs beside the zigzag's pieces for their length).
        for (std::size_t k = 0; k < p.size();) {
            if (near[k]) {
                ++k;
                continue;
            }
            std::size_t j = k;
            while (j + 1 < p.size() && !near[j + 1]) ++j;
            if (k > 0 && j + 1 < p.size() && u[j + 1] - u[k - 1] < 2.0 * double(width))
                std::fill(near.begin() + std::ptrdiff_t(k), near.begin() + std::ptrdiff_t(j) + 1, 1);
            k = j + 1;
        }
        for (std::size_t k = 0; k < p.size();) {  // runs of samples near an accepted stroke
            if (!near[k]) {
                ++k;
                continue;
            }
            std::size_t j = k;
            while (j + 1 < p.size() && near[j + 1]) ++j;
            // each sample stands for kStep of the stroke, as line_metrics counts a run
            if (u[j] - u[k] + double(kStep) >= double(min_run)) std::fill(cut.begin() + std::ptrdiff_t(k), cut.begin() + std::ptrdiff_t(j) + 1, 1);
            k = j + 1;
        }
        if (std::find(cut.begin(), cut.end(), 1) == cut.end()) {
            kept[i].push_back(s);
        } else {
            for (std::size_t k = 0; k < p.size();) {  // the stretches left, end to end
                if (cut[k]) {
                    ++k;
                    continue;
                }
                std::size_t j = k;
                while (j + 1 < p.size() && !cut[j + 1]) ++j;
                if (u[j] > u[k]) kept[i].push_back(sub_stroke(s, t, u[k], u[j]));
                k = j + 1;
            }
        }
        for (const Stroke& piece : kept[i]) {
            samples_of(piece, arc_lengths(piece), p, u);
            for (const glm::vec2& q : p) grid.add(q, int(i));
        }
    }
    std::vector<Stroke> out;
    for (std::vector<Stroke>& pieces : kept)
        for (Stroke& piece : pieces) out.push_back(std::move(piece));
    return out;
}

}  // namespace penink
