#include "drainage/flat_resolution.hpp"

#include <algorithm>
#include <cstring>

namespace penink {

namespace {

struct Flats {
    const std::vector<float>& z;
    const GridShape& g;
    std::vector<std::uint8_t>& dir;
    std::vector<std::uint32_t>& labels;
    std::int32_t* mask;  // the mask buffer seen as signed (Barnes's FlatMask)
    std::vector<std::uint32_t> low, high;
    std::vector<std::int32_t> flat_height;

    int col(std::uint32_t i) const { return int(i % g.cols); }
    int row(std::uint32_t i) const { return int(i / g.cols); }
    bool flat(std::uint32_t i) const {
        return g.valid[i] && dir[i] == 0 && !is_boundary_cell(g, col(i), row(i));
    }
    template <class F> void for_neighbours(std::uint32_t i, F&& f) const {
        const int c = col(i), r = row(i);
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
            const std::uint32_t n = std::uint32_t(nr) * g.cols + nc;
            if (g.valid[n]) f(n, k);
        }
    }
};

// Low edges: cells that drain (or are outlets) next to a flat cell of the same elevation.
// High edges: flat cells next to higher terrain.
void find_edges(Flats& s) {
    for (std::uint32_t i = 0; i < s.g.size(); ++i) {
        if (!s.flat(i)) continue;
        bool high = false;
        s.for_neighbours(i, [&](std::uint32_t n, int) {
            if (s.z[n] > s.z[i]) high = true;
            else if (s.z[n] == s.z[i] && !s.flat(n)) s.low.push_back(n);
        });
        if (high) s.high.push_back(i);
    }
    std::sort(s.low.begin(), s.low.end());
    s.low.erase(std::unique(s.low.begin(), s.low.end()), s.low.end());
}

// Labels each equal-elevation region reached from a low edge (Barnes's LabelFlat).
void label_flats(Flats& s) {
    std::uint32_t next = 1;
    std::vector<std::uint32_t> queue;
    for (std::uint32_t start : s.low) {
        if (s.labels[start]) continue;
        const std::uint32_t label = next++;
        const float h = s.z[start];
        queue.assign(1, start);
        s.labels[start] = label;
        for (std::size_t q = 0; q < queue.size(); ++q)
            s.for_neighbours(queue[q], [&](std::uint32_t n, int) {
                if (!s.labels[n] && s.z[n] == h) s.labels[n] = label, queue.push_back(n);
            });
    }
    s.flat_height.assign(next, 0);
}

// Breadth-first levels from `seeds` over flat cells of the same label; visit(cell, level) is
// called once per cell, returning false to skip a cell already set.
template <class Visit>
void bfs_levels(Flats& s, std::vector<std::uint32_t> level, Visit&& visit) {
    std::vector<std::uint32_t> next;
    for (std::int32_t loops = 1; !level.empty(); ++loops) {
        next.clear();
        for (std::uint32_t c : level) {
            if (!visit(c, loops)) continue;
            s.for_neighbours(c, [&](std::uint32_t n, int) {
                if (s.labels[n] == s.labels[c] && s.flat(n)) next.push_back(n);
            });
        }
        std::swap(level, next);
    }
}

void away_from_higher(Flats& s) {
    std::vector<std::uint32_t> seeds;
    for (std::uint32_t h : s.high)
        if (s.labels[h]) seeds.push_back(h);
    bfs_levels(s, std::move(seeds), [&](std::uint32_t c, std::int32_t loops) {
        if (s.mask[c] > 0) return false;
        s.mask[c] = loops;
        s.flat_height[s.labels[c]] = loops;
        return true;
    });
}

void towards_lower(Flats& s) {
    for (std::size_t i = 0; i < s.g.size(); ++i) s.mask[i] = -s.mask[i];
    bfs_levels(s, s.low, [&](std::uint32_t c, std::int32_t loops) {
        if (s.mask[c] > 0) return false;
        s.mask[c] = s.mask[c] < 0 ? s.flat_height[s.labels[c]] + s.mask[c] + 2 * loops
                                  : 2 * loops;
        return true;
    });
}

// Flat cells drain to the same-label neighbour of least combined gradient below their own.
std::size_t masked_directions(Flats& s) {
    std::size_t unresolved = 0;
    for (std::uint32_t i = 0; i < s.g.size(); ++i) {
        if (!s.labels[i] || !s.flat(i)) continue;
        std::int32_t best = s.mask[i];
        std::uint8_t code = 0;
        s.for_neighbours(i, [&](std::uint32_t n, int k) {
            if (s.labels[n] == s.labels[i] && s.mask[n] < best) best = s.mask[n], code = 1u << k;
        });
        s.dir[i] = code;
        unresolved += code == 0;
    }
    return unresolved;
}

}  // namespace

std::size_t resolve_flats(const std::vector<float>& z, const GridShape& g,
                          std::vector<std::uint8_t>& dir, std::vector<std::uint32_t>& labels,
                          std::vector<std::uint32_t>& mask) {
    labels.assign(g.size(), 0);
    mask.assign(g.size(), 0);
    Flats s{z, g, dir, labels, reinterpret_cast<std::int32_t*>(mask.data()), {}, {}, {}};
    find_edges(s);
    label_flats(s);
    away_from_higher(s);
    towards_lower(s);
    std::size_t unresolved = masked_directions(s);
    // flats no low edge reaches (impossible after priority-flood) stay without direction
    for (std::uint32_t i = 0; i < g.size(); ++i)
        if (!labels[i] && s.flat(i)) ++unresolved;
    return unresolved;
}

}  // namespace penink
