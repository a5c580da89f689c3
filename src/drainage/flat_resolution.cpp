#include "drainage/flat_resolution.hpp"

#include "drainage/priority_flood.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <climits>

#include "core/bit_blocks.hpp"
#include "core/parallel_chunks.hpp"

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

    bool flat(std::uint32_t i) const { return flags[i] & flat_interior; }
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

// One bit per cell: a BFS's own "seen" marks (the two BFS run at once and leave `flags` alone).
struct CellBits {
    std::vector<std::uint64_t> w;
    explicit CellBits(std::size_t n) : w((n + 63) / 64, 0) {}
    bool test_and_set(std::uint32_t i) {
        const std::uint64_t b = std::uint64_t(1) << (i & 63), old = w[i >> 6];
        w[i >> 6] = old | b;
        return old & b;
    }
    bool test(std::uint32_t i) const { return w[i >> 6] >> (i & 63) & 1; }
};

// Low edges: cells with a direction (or outlets) next to a flat cell of the same elevation, each
// once, in the order a scan of the cells first meets them. High edges: flat cells next to higher
// terrain, in cell order. Rows in parallel chunks (low candidates with repeats), joined in chunk
// order, then the repeats dropped. Returns the number of flat cells.
std::size_t find_edges(Flats& s) {
    std::atomic<std::size_t> flat_cells{0};
    parallel_chunks(s.g.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1) {
        std::size_t n = 0;
        for (std::size_t i = i0; i < i1; ++i)
            if (s.dir[i] == 0 && s.g.valid[i] && !(s.flags[i] & fill_boundary)) s.flags[i] |= flat_interior, ++n;
        flat_cells += n;
    });
    const std::size_t cols = std::size_t(s.g.cols), rows = std::size_t(s.g.rows), per = chunk_length(rows, 64);
    std::vector<std::vector<std::uint32_t>> low((rows + per - 1) / per), high(low.size());
    parallel_chunks(rows, 64, [&](std::size_t r0, std::size_t r1) {
        std::vector<std::uint32_t>&lo = low[r0 / per], &hi = high[r0 / per];
        for (std::uint32_t i = std::uint32_t(r0 * cols); i < r1 * cols; ++i) {
            if (!s.flat(i)) continue;
            bool up = false;
            s.around_flat(i, [&](std::uint32_t n, int) {
                if (s.z[n] > s.z[i]) up = true;
                else if (s.z[n] == s.z[i] && !s.flat(n)) lo.push_back(n);
            });
            if (up) hi.push_back(i);
        }
    });
    CellBits seen(s.g.size());
    for (std::size_t k = 0; k < low.size(); ++k) {
        for (std::uint32_t n : low[k])
            if (!seen.test_and_set(n)) s.low.push_back(n);
        s.high.insert(s.high.end(), high[k].begin(), high[k].end());
    }
    return flat_cells;
}

// Breadth-first levels 1, 2, ... from `level` over flat cells of the same elevation not yet in
// `seen` (seeds are flat cells); visit(cell, level) is called once per cell.
template <class Visit>
void bfs_levels(const Flats& s, std::vector<std::uint32_t> level, CellBits& seen, Visit&& visit) {
    std::vector<std::uint32_t> next;
    for (std::uint32_t c : level) seen.test_and_set(c);
    for (std::int32_t loops = 1; !level.empty(); ++loops) {
        next.clear();
        for (std::uint32_t c : level) {
            visit(c, loops);
            // most neighbours inside a flat were seen already: their bit (a small array) before
            // their elevation and flags
            auto reach = [&](std::uint32_t n, int) {
                if (!seen.test(n) && s.z[n] == s.z[c] && s.flat(n)) seen.test_and_set(n), next.push_back(n);
            };
            if (loops == 1) s.around(c, reach);  // low edges may lie on the border, flat cells never
            else s.around_flat(c, reach);
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

// Flat cell i drains to the first such neighbour in code order (noted in `ties` when several).
std::uint8_t masked_direction(const Flats& s, std::uint32_t i, std::vector<std::uint32_t>& ties) {
    const unsigned set = least_gradient(s.z, s.flags, s.mask, s.off.data(), i);
    // raised cells are re-aimed or keep this code as an outflow path (depression_drainage.hpp)
    if ((set & (set - 1)) != 0 && s.ties && !(s.flags[i] & fill_raised)) ties.push_back(i);
    return std::uint8_t(set & -set);
}

}  // namespace

unsigned flat_candidates(const std::vector<float>& z, const GridShape& g,
                         const std::vector<std::uint8_t>& flags,
                         const CellWords& mask, std::size_t i) {
    return least_gradient(z.data(), flags.data(), reinterpret_cast<const std::int32_t*>(mask.data()),
                          d8_offsets(g).data(), std::uint32_t(i));
}

namespace {

// The cells the towards-lower BFS reached (low edges first, level 1) with their level.
struct Reached {
    std::uint32_t cell;
    std::int32_t level;
};

// Combined gradient of every reached cell from its towards-lower level and the away-from-higher
// distance in mask (cells marked in `high`): 2 * level - away; low edges INT32_MIN; each reached
// cell's flat_seen_low bit set. Parallel chunks (each cell written once); returns how many reached
// cells the away pass had seen.
std::size_t combine(Flats& s, const std::vector<Reached>& low, const CellBits& high) {
    std::atomic<std::size_t> seen_high{0};
    parallel_chunks(low.size(), 1 << 16, [&](std::size_t k0, std::size_t k1) {
        std::size_t n = 0;
        for (std::size_t k = k0; k < k1; ++k) {
            const auto [c, level] = low[k];
            const bool h = high.w[c >> 6] >> (c & 63) & 1;
            n += h && level > 1;
            s.mask[c] = level == 1 ? INT32_MIN : 2 * level - (h ? s.mask[c] : 0);
            s.flags[c] |= flat_seen_low;
        }
        seen_high += n;
    });
    return seen_high;
}

// Every reached flat cell's direction from the combined gradients (its neighbours' all final), in
// parallel chunks in cell order (raised cells only with raised_too), the tied ones appended to
// s.ties; returns how many got none.
std::size_t settle_flats(Flats& s, bool raised_too) {
    std::atomic<std::size_t> unresolved{0};
    constexpr std::uint8_t settle = flat_interior | flat_seen_low;
    const std::uint8_t look = settle | (raised_too ? 0 : fill_raised);
    const std::vector<std::uint32_t> tied = parallel_collect<std::uint32_t>(
        s.g.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1, std::vector<std::uint32_t>& out) {
            std::size_t none = 0;
            for (std::size_t i = i0; i < i1; ++i)
                if ((s.flags[i] & look) == settle) none += (s.dir[i] = masked_direction(s, std::uint32_t(i), out)) == 0;
            unresolved += none;
        });
    if (s.ties) s.ties->insert(s.ties->end(), tied.begin(), tied.end());
    return unresolved;
}

}  // namespace

// The away-from-higher BFS (distances into mask) and the towards-lower BFS (levels kept in a
// list) on two threads, each with its own seen bits; then the gradients combined and every flat
// cell reached settled (its neighbours' gradients all final), in the list's order.
std::size_t resolve_flats(const GridShape& g, RoutingArrays& arrays, CellWords& mask, bool raised_too) {
    mask.resize(g.size());
    Flats s{arrays.z.data(), g, arrays.dir.data(), arrays.flags.data(), reinterpret_cast<std::int32_t*>(mask.data()),
            d8_offsets(g), {}, {}, &arrays.ties};
    const std::size_t flat_cells = find_edges(s);
    CellBits high(g.size()), low_seen(g.size());
    std::size_t high_cells = 0;
    // what the towards-lower search can reach (its low edges and flat cells), reserved: grown
    // instead, it copied itself and faulted its pages twice over (jacksboro refined 29 times:
    // tens of millions of flat cells, seconds of the flats' time)
    std::vector<Reached> low;
    low.reserve(s.low.size() + flat_cells);
    run_beside([&] { bfs_levels(s, s.high, high, [&](std::uint32_t c, std::int32_t h) { s.mask[c] = h, ++high_cells; }); },
               [&] { bfs_levels(s, s.low, low_seen, [&](std::uint32_t c, std::int32_t l) { low.push_back({c, l}); }); });
    const std::size_t reached_high = combine(s, low, high);
    // the away-from-higher search's cells get flat_seen_high (flat_seen_low came with combine:
    // what flat_candidates and d8_ties read afterwards)
    set_flag_at_bits(high.w, s.flags, flat_seen_high);
    // flats no low edge reaches (impossible after priority-flood) stay without direction
    return settle_flats(s, raised_too) + (high_cells - reached_high);
}

}  // namespace penink
