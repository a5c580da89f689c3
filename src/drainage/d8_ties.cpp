#include "drainage/d8_ties.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <bit>
#include <limits>

#include "drainage/d8_steepest.hpp"
#include "drainage/depression_drainage.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/priority_flood.hpp"

namespace penink {

namespace {

struct Ties {
    const std::vector<float>& filled;
    const std::vector<std::uint8_t>& flags;
    const CellWords& orig;
    const GridShape& g;
    D8Steps st;
    const std::vector<std::uint8_t>& dir;
    const CellWords& flat_mask;  // flat gradients as int32 (flat_resolution.hpp)
    int depth;

    float original(std::size_t n) const { return original_z(filled, flags, orig, n); }
    std::int32_t gradient(std::size_t i) const { return std::int32_t(flat_mask[i]); }
    bool flat_cell(std::size_t i) const {
        return (flags[i] & flat_seen_low) && !(flags[i] & fill_raised) && gradient(i) != INT32_MIN;
    }
    // Settling order: lower cells first; on one level D8 cells, then flat cells nearer the exit,
    // then by index (duplicates end up next to each other).
    bool before(std::uint32_t a, std::uint32_t b) const {
        if (filled[a] != filled[b]) return filled[a] < filled[b];
        const std::int64_t ra = rank(a), rb = rank(b);
        return ra != rb ? ra < rb : a < b;
    }
    std::int64_t rank(std::size_t i) const {
        return flat_cell(i) ? std::int64_t(gradient(i)) - INT32_MIN + 1 : 0;
    }

    // Bit k set for every admissible neighbour k with the steepest slope (stage rules above).
    unsigned steepest_set(std::size_t i) const {
        if (flat_cell(i)) return flat_candidates(filled, g, flags, flat_mask, i);
        const int c = int(i % std::size_t(g.cols)), r = int(i / std::size_t(g.cols));
        const float zi = original(i), level = filled[i];
        const bool raised = flags[i] & fill_raised;
        auto zn = [&](std::size_t n) { return original(n); };
        auto ok = [&](std::size_t n) { return raised ? original(n) < zi : filled[n] < level; };
        return d8_steepest(zi, g, c, r, st, zn, ok).steepest;
    }

    // Original elevations along the path from n, `depth` entries; past the grid's edge: -inf.
    void path_key(std::size_t n, float* key) const {
        for (int j = 0; j < depth; ++j) {
            key[j] = original(n);
            if (!dir[n]) {
                std::fill(key + j + 1, key + depth, -std::numeric_limits<float>::infinity());
                return;
            }
            n = d8_target(g, n, dir[n]);
        }
    }

    std::uint8_t choose(std::size_t i, unsigned set) const {
        std::array<float, 64> best{}, key{};
        std::uint8_t code = 0;
        for (int k = 0; k < 8; ++k) {
            if (!(set >> k & 1)) continue;
            path_key(std::size_t(std::ptrdiff_t(i) + st.off[k]), key.data());
            if (!code || std::lexicographical_compare(key.begin(), key.begin() + depth, best.begin(),
                                                      best.begin() + depth))
                best = key, code = std::uint8_t(1u << k);
        }
        return code;
    }
};

}  // namespace

std::size_t break_d8_ties(const RoutingGrid& grid, RoutingArrays& arrays, const CellWords& flat_mask, int depth) {
    std::vector<std::uint32_t>& ties = arrays.ties;
    const std::vector<std::uint8_t>& flags = arrays.flags;
    std::vector<std::uint8_t>& dir = arrays.dir;
    Ties t{arrays.z, flags, arrays.orig_bits, grid.shape, d8_steps(grid.shape, grid.dx, grid.dy), dir, flat_mask,
           std::clamp(depth, 1, 64)};
    std::sort(ties.begin(), ties.end(), [&](std::uint32_t a, std::uint32_t b) { return t.before(a, b); });
    ties.erase(std::unique(ties.begin(), ties.end()), ties.end());
    std::size_t changed = 0;
    for (const std::uint32_t i : ties) {
        if (flags[i] & depression_outflow) continue;
        const unsigned set = t.steepest_set(i);
        if ((set & (set - 1)) == 0) continue;  // fewer than two neighbours
        const std::uint8_t code = t.choose(i, set);
        changed += code != dir[i];
        dir[i] = code;
    }
    return changed;
}

}  // namespace penink
