// Marching triangles at the sea level (sea_level_contour.hpp).
#include "surface/sea_level_contour.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>

namespace penink {

namespace {

// Crossing points of the shore on mesh edges, and the segments joining them (at most two per
// point: an edge lies in at most two triangles).
class ShoreGraph {
public:
    ShoreGraph(const GridNodes& nodes) : n_(nodes), sea_(double(nodes.sea_z())) {}

    bool land(std::size_t i) const { return drawn(i) > sea_; }

    // The segment of triangle (a, b, c) (valid nodes), if the shore crosses it.
    void triangle(std::size_t a, std::size_t b, std::size_t c) {
        std::array<int, 2> ends{};
        int k = 0;
        for (const auto& [p, q] : {std::pair(a, b), std::pair(b, c), std::pair(c, a)})
            if (land(p) != land(q) && k < 2) ends[std::size_t(k++)] = point(p, q);
        if (k != 2) return;  // 0: all land or all water; a triangle crosses on two edges or none
        link(ends[0], ends[1]);
        link(ends[1], ends[0]);
    }

    std::vector<ShoreLine> chain() const {
        std::vector<ShoreLine> out;
        std::vector<std::uint8_t> seen(points_.size(), 0);
        const auto walk = [&](int start) {
            ShoreLine line;
            int prev = -1, at = start;
            while (at >= 0 && !seen[std::size_t(at)]) {
                seen[std::size_t(at)] = 1;
                add(line, at);
                const std::array<int, 2>& nb = next_[std::size_t(at)];
                const int go = nb[0] != prev ? nb[0] : nb[1];
                prev = at, at = go;
            }
            if (at == start && line.points.size() > 2 && line.points.back() != line.points.front()) {  // closed
                line.points.push_back(line.points.front());
                line.ground.push_back(line.ground.front());
            }
            if (line.points.size() >= 2) out.push_back(std::move(line));
        };
        for (std::size_t i = 0; i < points_.size(); ++i)  // open lines from their ends
            if (!seen[i] && (next_[i][0] < 0 || next_[i][1] < 0)) walk(int(i));
        for (std::size_t i = 0; i < points_.size(); ++i)  // then the loops
            if (!seen[i]) walk(int(i));
        return out;
    }

private:
    const GridNodes& n_;
    double sea_;
    std::unordered_map<std::uint64_t, int> ids_;  // edge key -> point
    std::vector<std::pair<glm::vec3, float>> points_;  // point, ground
    std::vector<std::array<int, 2>> next_;

    // Drawn height before the water clamp, as GridNodes::at computes it.
    double drawn(std::size_t i) const {
        const float z = n_.z_scale != 1.0 ? float(double(n_.pos[i].z) * n_.z_scale) : n_.pos[i].z;
        return double(z);
    }

    int point(std::size_t p, std::size_t q) {
        const std::size_t lo = std::min(p, q), hi = std::max(p, q);
        // edges of the NW-SE split join a node to its east, south or south-east neighbour
        const std::uint64_t dir = hi == lo + 1 ? 0 : hi == lo + std::size_t(n_.cols) ? 1 : 2;
        const std::uint64_t key = std::uint64_t(lo) * 3 + dir;
        const auto [it, added] = ids_.try_emplace(key, int(points_.size()));
        if (!added) return it->second;
        const std::size_t w = land(p) ? q : p, l = land(p) ? p : q;  // water node, land node
        const double zw = drawn(w), zl = drawn(l);
        const double t = std::clamp((sea_ - zw) / (zl - zw), 0.0, 1.0);
        const glm::dvec3 a(n_.pos[w]), b(n_.pos[l]);
        const glm::vec3 at(float(a.x + t * (b.x - a.x)), float(a.y + t * (b.y - a.y)), float(sea_));
        points_.push_back({at, float(sea_ + t * (zl - sea_))});
        next_.push_back({-1, -1});
        return it->second;
    }

    void link(int from, int to) {
        std::array<int, 2>& nb = next_[std::size_t(from)];
        if (nb[0] == to || nb[1] == to) return;
        (nb[0] < 0 ? nb[0] : nb[1]) = to;
    }

    // Appends point i; a shore through a node at the sea level crosses several of its edges at the
    // node itself: the repeats are left out.
    void add(ShoreLine& line, int i) const {
        if (!line.points.empty() && line.points.back() == points_[std::size_t(i)].first) return;
        line.points.push_back(points_[std::size_t(i)].first);
        line.ground.push_back(points_[std::size_t(i)].second);
    }
};

}  // namespace

std::vector<ShoreLine> sea_level_contour(const GridNodes& nodes, GridWindow w) {
    if (!nodes.has_sea() || !nodes.pos || !nodes.valid) return {};
    w.c0 = std::max(w.c0, 0), w.r0 = std::max(w.r0, 0);
    w.c1 = std::min(w.c1, nodes.cols), w.r1 = std::min(w.r1, nodes.rows);
    nodes.need(w);
    ShoreGraph graph(nodes);
    for (int r = w.r0; r + 1 < w.r1; ++r)
        for (int c = w.c0; c + 1 < w.c1; ++c) {
            const std::size_t nw = nodes.index(c, r), ne = nodes.index(c + 1, r);
            const std::size_t sw = nodes.index(c, r + 1), se = nodes.index(c + 1, r + 1);
            const auto ok = [&](std::size_t i) { return nodes.valid[i] != 0; };
            // the cell's two triangles as surface_mesh.hpp makes them: {NW, SW, SE}, {NW, SE, NE}
            if (ok(nw) && ok(sw) && ok(se)) graph.triangle(nw, sw, se);
            if (ok(nw) && ok(se) && ok(ne)) graph.triangle(nw, se, ne);
        }
    return graph.chain();
}

}  // namespace penink
