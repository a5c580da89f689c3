#include "drainage/priority_flood.hpp"

#include <queue>

namespace penink {

namespace {

struct Node {
    float z;
    std::uint32_t i;
    // min-heap on elevation, then index (deterministic order for equal elevations)
    bool operator>(const Node& o) const { return z > o.z || (z == o.z && i > o.i); }
};

using OpenQueue = std::priority_queue<Node, std::vector<Node>, std::greater<Node>>;

void seed_boundary(const std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& closed,
                   OpenQueue& open) {
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (!g.valid[i] || !is_boundary_cell(g, c, r)) continue;
            closed[i] = 1;
            open.push({z[i], std::uint32_t(i)});
        }
}

}  // namespace

std::size_t priority_flood_fill(std::vector<float>& z, const GridShape& g,
                                std::vector<RaisedCell>& raised) {
    std::vector<std::uint8_t> closed(g.size(), 0);
    OpenQueue open;
    std::queue<std::uint32_t> pit;
    seed_boundary(z, g, closed, open);
    std::size_t visited = 0;
    while (!open.empty() || !pit.empty()) {
        std::uint32_t c;
        if (!pit.empty()) c = pit.front(), pit.pop();
        else c = open.top().i, open.pop();
        ++visited;
        const int cc = int(c % g.cols), cr = int(c / g.cols);
        for (int k = 0; k < 8; ++k) {
            const int nc = cc + d8_dc[k], nr = cr + d8_dr[k];
            if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
            const std::uint32_t n = std::uint32_t(nr) * g.cols + nc;
            if (closed[n] || !g.valid[n]) continue;
            closed[n] = 1;
            if (z[n] <= z[c]) {
                if (z[n] < z[c]) raised.push_back({n, z[n]}), z[n] = z[c];
                pit.push(n);
            } else {
                open.push({z[n], n});
            }
        }
    }
    return visited;
}

void restore_raised(std::vector<float>& z, const std::vector<RaisedCell>& raised) {
    for (const RaisedCell& r : raised) z[r.index] = r.z;
}

}  // namespace penink
