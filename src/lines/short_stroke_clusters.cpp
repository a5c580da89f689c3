// Star-like clusters of short strokes thinned (short_stroke_clusters.hpp).
#include "lines/short_stroke_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "lines/line_metrics.hpp"

namespace penink {

namespace {

struct Clusters {
    std::vector<std::size_t> order;      // short strokes, strongest first
    std::vector<std::uint8_t> dropped;   // per stroke
    std::size_t clusters = 0;
};

// Each short stroke's ends in a grid of `radius` cells; strokes taken strongest first, each kept
// one whose end has two or more other live short strokes' ends within radius drops them.
Clusters find_clusters(const std::vector<Stroke>& strokes, float short_px, float radius) {
    Clusters c;
    c.dropped.assign(strokes.size(), 0);
    std::vector<float> length(strokes.size(), 0.0f);
    for (std::size_t i = 0; i < strokes.size(); ++i) {
        if (strokes[i].points.size() < 2) continue;
        length[i] = float(stroke_length(strokes[i]));
        if (length[i] < short_px) c.order.push_back(i);
    }
    std::stable_sort(c.order.begin(), c.order.end(), [&](std::size_t a, std::size_t b) {
        if (strokes[a].strength != strokes[b].strength) return strokes[a].strength > strokes[b].strength;
        return length[a] > length[b];
    });
    if (!(radius > 0.0f)) return c;
    const auto cell_of = [&](glm::vec2 p) {
        return glm::ivec2(std::int32_t(std::floor(p.x / radius)), std::int32_t(std::floor(p.y / radius)));
    };
    const auto key = [](glm::ivec2 cell) {
        return (std::uint64_t(std::uint32_t(cell.x)) << 32) | std::uint32_t(cell.y);
    };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;  // cell -> short strokes with an end there
    for (std::size_t i : c.order)
        for (const glm::vec2& e : {strokes[i].points.front(), strokes[i].points.back()}) grid[key(cell_of(e))].push_back(i);
    std::vector<std::size_t> near;
    for (std::size_t i : c.order) {
        if (c.dropped[i]) continue;
        for (const glm::vec2& e : {strokes[i].points.front(), strokes[i].points.back()}) {
            near.clear();
            const glm::ivec2 cell = cell_of(e);
            for (std::int32_t dy = -1; dy <= 1; ++dy)
                for (std::int32_t dx = -1; dx <= 1; ++dx) {
                    const auto it = grid.find(key(cell + glm::ivec2(dx, dy)));
                    if (it == grid.end()) continue;
                    for (std::size_t j : it->second) {
                        if (j == i || c.dropped[j]) continue;
                        const Stroke& s = strokes[j];
                        if (glm::distance(s.points.front(), e) <= radius || glm::distance(s.points.back(), e) <= radius)
                            near.push_back(j);
                    }
                }
            std::sort(near.begin(), near.end());
            near.erase(std::unique(near.begin(), near.end()), near.end());
            if (near.size() < 2) continue;  // with i, fewer than three: a junction or a pair, not a star
            ++c.clusters;
            for (std::size_t j : near) c.dropped[j] = 1;
        }
    }
    return c;
}

}  // namespace

std::size_t count_star_clusters(const std::vector<Stroke>& strokes, float short_px, float radius) {
    return find_clusters(strokes, short_px, radius).clusters;
}

std::vector<Stroke> thin_star_clusters(std::vector<Stroke> strokes, float short_px, float radius) {
    const Clusters c = find_clusters(strokes, short_px, radius);
    std::vector<Stroke> out;
    out.reserve(strokes.size());
    for (std::size_t i = 0; i < strokes.size(); ++i)
        if (!c.dropped[i]) out.push_back(std::move(strokes[i]));
    return out;
}

}  // namespace penink
