#include "drainage/flat_resolution.hpp"

#include "drainage/priority_flood.hpp"

#include <array>
#include <bit>
#include <climits>

namespace penink {

namespace {

struct Flats {
    const float* z;
    const GridShape& g;
    std::uint8_t* dir;
    std::uint8_t* flags;
    std::int32_t* mask;  // away-from-higher distance, then the combined gradient
    std::array<std::ptrdiff_t, 8> off;
    std::vector<std::uint32_t> low, high;
    std::vector<std::uint32_t>* ties;  // flat cells with two or more neighbours of least mask

    bool flat(std::uint32_t i) const {
        return dir[i] == 0 && g.valid[i] && !(flags[i] & fill_boundary);
    }
    // Valid neighbours of any cell (bounds checked: low edges may lie on the border).
    template <class F> void around(std::uint32_t i, F&& f) const {
        const int c = int(i % std::uint32_t(g.cols)), r = int(i / std::uint32_t(g.cols));
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
            const std::uint32_t n = std::uint32_t(nr) * std::uint32_t(g.cols) + std::uint32_t(nc);
            if (g.valid[n]) f(n, k);
        }
    }
    // Neighbours of a flat cell: all 8 exist and are valid (a flat cell is not a boundary cell).
    template <class F> void around_flat(std::uint32_t i, F&& f) const {
        for (int k = 0; k < 8; ++k) f(std::uint32_t(std::ptrdiff_t(i) + off[k]), k);
    }
};

// Low edges: cells with a direction (or outlets) next to a flat cell of the same elevation.
// High edges: flat cells next to higher terrain. One scan of the direction bytes.
void find_edges(Flats& s) {
    for (std::uint32_t i = 0; i < s.g.size(); ++i) {
        if (s.dir[i] || !s.flat(i)) continue;
        bool high = false;
        s.around_flat(i, [&](std::uint32_t n, int) {
            if (s.z[n] > s.z[i]) high = true;
            else if (s.z[n] == s.z[i] && !(s.flags[n] & flat_seen_low) && !s.flat(n))
                s.flags[n] |= flat_seen_low, s.low.push_back(n);
        });
        if (high) s.high.push_back(i);
    }
}

// Breadth-first levels 1, 2, ... from `level` over flat cells of the same elevation not yet
// marked with `bit` (seeds are flat cells); visit(cell, level) is called once per cell.
template <class Visit>
void bfs_levels(Flats& s, std::vector<std::uint32_t> level, std::uint8_t bit, Visit&& visit) {
    std::vector<std::uint32_t> next;
    for (std::uint32_t c : level) s.flags[c] |= bit;
    for (std::int32_t loops = 1; !level.empty(); ++loops) {
        next.clear();
        for (std::uint32_t c : level) {
            visit(c, loops);
            s.around_flat(c, [&](std::uint32_t n, int) {
                if (!(s.flags[n] & bit) && s.z[n] == s.z[c] && s.flat(n))
                    s.flags[n] |= bit, next.push_back(n);
            });
        }
        std::swap(level, next);
    }
}

// Bit k for every same-elevation neighbour k of flat cell i with the least gradient below its own.
unsigned least_gradient(const float* z, const std::uint8_t* flags, const std::int32_t* mask,
                        const std::ptrdiff_t* off, std::uint32_t i) {
    std::int32_t best = mask[i];
    unsigned set = 0;
    for (int k = 0; k < 8; ++k) {
        const std::uint32_t n = std::uint32_t(std::ptrdiff_t(i) + off[k]);
        if (z[n] != z[i] || !(flags[n] & flat_seen_low)) continue;
        if (mask[n] < best) best = mask[n], set = 1u << k;
        else if (set && mask[n] == best) set |= 1u << k;
    }
    return set;
}

// Flat cell i drains to the first such neighbour in code order (noted in s.ties when several).
std::uint8_t masked_direction(const Flats& s, std::uint32_t i) {
    const unsigned set = least_gradient(s.z, s.flags, s.mask, s.off.data(), i);
    // raised cells are re-aimed or keep this code as an outflow path (depression_drainage.hpp)
    if ((set & (set - 1)) != 0 && s.ties && !(s.flags[i] & fill_raised)) s.ties->push_back(i);
    return std::uint8_t(set & -set);
}

}  // namespace

unsigned flat_candidates(const std::vector<float>& z, const GridShape& g,
                         const std::vector<std::uint8_t>& flags,
                         const std::vector<std::uint32_t>& mask, std::size_t i) {
    return least_gradient(z.data(), flags.data(), reinterpret_cast<const std::int32_t*>(mask.data()),
                          d8_offsets(g).data(), std::uint32_t(i));
}

namespace {

// Towards-lower BFS from the low edges (level 1, mask = lowest) combined with the away-from-higher
// distance already in `mask`; a cell's direction is set once its neighbours' levels (one more
// than its own at most) are final. Returns {cells left without a direction, cells reached that
// the away-from-higher pass had seen}.
std::pair<std::size_t, std::size_t> towards_lower(Flats& s) {
    std::size_t unresolved = 0, seen_high = 0;
    std::vector<std::uint32_t> level = s.low, next;
    auto settle = [&](const std::vector<std::uint32_t>& cells) {
        for (std::uint32_t c : cells) unresolved += (s.dir[c] = masked_direction(s, c)) == 0;
    };
    for (std::uint32_t c : level) s.flags[c] |= flat_seen_low, s.mask[c] = INT32_MIN;
    for (std::int32_t loops = 2; !level.empty(); ++loops) {
        next.clear();
        auto reach = [&](std::uint32_t c, std::uint32_t n) {
            if ((s.flags[n] & flat_seen_low) || s.z[n] != s.z[c] || !s.flat(n)) return;
            s.flags[n] |= flat_seen_low, next.push_back(n);
            const bool high = s.flags[n] & flat_seen_high;
            seen_high += high;
            s.mask[n] = 2 * loops - (high ? s.mask[n] : 0);
        };
        for (std::uint32_t c : level) {  // low edges may lie on the border, flat cells never
            if (loops == 2) s.around(c, [&](std::uint32_t n, int) { reach(c, n); });
            else s.around_flat(c, [&](std::uint32_t n, int) { reach(c, n); });
        }
        if (loops > 2) settle(level);  // level loops-1: every neighbour's mask is set now
        std::swap(level, next);
    }
    return {unresolved, seen_high};
}

}  // namespace

std::size_t resolve_flats(const std::vector<float>& z, const GridShape& g,
                          std::vector<std::uint8_t>& dir, std::vector<std::uint8_t>& flags,
                          std::vector<std::uint32_t>& mask, std::vector<std::uint32_t>* ties) {
    mask.resize(g.size());
    Flats s{z.data(), g, dir.data(), flags.data(), reinterpret_cast<std::int32_t*>(mask.data()),
            d8_offsets(g), {}, {}, ties};
    find_edges(s);
    std::size_t high_cells = 0;
    bfs_levels(s, s.high, flat_seen_high, [&](std::uint32_t c, std::int32_t h) {
        s.mask[c] = h, ++high_cells;
    });
    for (std::uint32_t c : s.low) s.flags[c] &= std::uint8_t(~flat_seen_low);
    const auto [unresolved, reached_high] = towards_lower(s);
    // flats no low edge reaches (impossible after priority-flood) stay without direction
    return unresolved + (high_cells - reached_high);
}

}  // namespace penink
