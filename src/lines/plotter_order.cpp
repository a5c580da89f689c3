#include "lines/plotter_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "lines/simplify.hpp"

namespace penink {

double pen_up_travel(const std::vector<Stroke>& strokes, glm::vec2 home) {
    double t = 0.0;
    glm::vec2 pen = home;
    for (const Stroke& s : strokes) {
        if (s.points.empty()) continue;
        t += glm::length(s.points.front() - pen);
        pen = s.points.back();
    }
    return t;
}

double pen_down_length(const std::vector<Stroke>& strokes) {
    double l = 0.0;
    for (const Stroke& s : strokes)
        for (std::size_t i = 1; i < s.points.size(); ++i) l += glm::length(s.points[i] - s.points[i - 1]);
    return l;
}

namespace {

// Uniform grid over the stroke ends (end id = 2*stroke + 0 for start, 1 for end).
struct EndGrid {
    glm::vec2 lo{0.0f};
    float cell = 1.0f;
    int nx = 1, ny = 1;
    std::vector<std::vector<int>> cells;
    const std::vector<glm::vec2>* ends = nullptr;

    glm::ivec2 cell_of(glm::vec2 p) const {
        int cx = std::clamp(int(std::floor((p.x - lo.x) / cell)), 0, nx - 1);
        int cy = std::clamp(int(std::floor((p.y - lo.y) / cell)), 0, ny - 1);
        return {cx, cy};
    }
};

EndGrid make_grid(const std::vector<glm::vec2>& ends, const std::vector<int>& ids) {
    EndGrid g;
    g.ends = &ends;
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int e : ids) lo = glm::min(lo, ends[e]), hi = glm::max(hi, ends[e]);
    glm::vec2 size = glm::max(hi - lo, glm::vec2(1.0f));
    g.lo = lo;
    g.cell = std::max(1.0f, std::sqrt(size.x * size.y / float(std::max<std::size_t>(ids.size(), 1))));
    g.nx = std::min(4096, int(size.x / g.cell) + 1);
    g.ny = std::min(4096, int(size.y / g.cell) + 1);
    g.cell = std::max(g.cell, std::max(size.x / float(g.nx), size.y / float(g.ny)));
    g.cells.resize(std::size_t(g.nx) * g.ny);
    for (int e : ids) {
        glm::ivec2 c = g.cell_of(ends[e]);
        g.cells[std::size_t(c.y) * g.nx + c.x].push_back(e);
    }
    return g;
}

// Nearest unused end to p (ties: lower id); searches rings of cells until no nearer can exist.
int nearest_end(EndGrid& g, glm::vec2 p, const std::vector<char>& used) {
    glm::ivec2 c = g.cell_of(p);
    int best = -1;
    float best_d = std::numeric_limits<float>::infinity();
    int max_r = std::max(g.nx, g.ny);
    for (int r = 0; r <= max_r; ++r) {
        for (int y = c.y - r; y <= c.y + r; ++y)
            for (int x = c.x - r; x <= c.x + r; ++x) {
                if (std::max(std::abs(x - c.x), std::abs(y - c.y)) != r) continue;
                if (x < 0 || y < 0 || x >= g.nx || y >= g.ny) continue;
                auto& cell = g.cells[std::size_t(y) * g.nx + x];
                std::erase_if(cell, [&used](int e) { return used[e / 2] != 0; });
                for (int e : cell) {
                    float d = glm::length((*g.ends)[e] - p);
                    if (d < best_d || (d == best_d && e < best)) best = e, best_d = d;
                }
            }
        // Points outside the searched square are at least r * cell away (p inside cell c).
        if (best >= 0 && best_d <= float(r) * g.cell) break;
    }
    return best;
}

void reverse_stroke(Stroke& s) {
    std::reverse(s.points.begin(), s.points.end());
    std::reverse(s.depth.begin(), s.depth.end());
    std::reverse(s.weight.begin(), s.weight.end());
}

}  // namespace

PlotterStats order_for_plotter(std::vector<Stroke>& strokes, glm::vec2 home) {
    PlotterStats st;
    st.count = strokes.size();
    st.length = pen_down_length(strokes);
    st.travel_before = pen_up_travel(strokes, home);
    std::vector<glm::vec2> ends(2 * strokes.size());
    std::vector<int> ids;
    for (std::size_t i = 0; i < strokes.size(); ++i) {
        if (strokes[i].points.empty()) continue;
        ends[2 * i] = strokes[i].points.front(), ends[2 * i + 1] = strokes[i].points.back();
        ids.push_back(int(2 * i));
        if (!is_closed(strokes[i])) ids.push_back(int(2 * i + 1));
    }
    EndGrid g = make_grid(ends, ids);
    std::vector<char> used(strokes.size(), 0);
    std::vector<Stroke> out;
    out.reserve(strokes.size());
    glm::vec2 pen = home;
    for (std::size_t k = 0; k < ids.size(); ++k) {
        int e = ids.empty() ? -1 : nearest_end(g, pen, used);
        if (e < 0) break;
        used[e / 2] = 1;
        out.push_back(std::move(strokes[e / 2]));
        if (e % 2 == 1) reverse_stroke(out.back());
        pen = out.back().points.back();
    }
    for (std::size_t i = 0; i < strokes.size(); ++i)
        if (strokes[i].points.empty() && !used[i]) out.push_back(std::move(strokes[i]));
    strokes = std::move(out);
    st.travel_after = pen_up_travel(strokes, home);
    return st;
}

}  // namespace penink
