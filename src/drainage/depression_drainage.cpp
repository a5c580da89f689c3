#include "drainage/depression_drainage.hpp"

#include <atomic>
#include <bit>
#include <utility>
#include <vector>

#include "core/bit_blocks.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/d8_steepest.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/priority_flood.hpp"

namespace penink {

namespace {

struct Depressions {
    const std::vector<float>& filled;
    std::vector<std::uint8_t>& flags;
    const CellWords& orig;
    const CellWords& flat_mask;
    const GridShape& g;
    D8Steps st;
    std::vector<std::uint8_t>& dir;

    float original(std::size_t n) const { return original_z(filled, flags, orig, n); }

    // Steepest original descent of raised cell i. A raised cell is never a boundary cell, so
    // its 8 neighbours exist and are valid.
    D8Choice descent(std::size_t i) const {
        return d8_steepest_dense(std::bit_cast<float>(orig[i]), i, st,
                                 [&](std::size_t n) { return original(n); });
    }

    // Marks the flat-resolved path from low point p until it steps down off the filled flat,
    // reaches an outlet or joins a path already marked (`claimed`: the first path to reach a
    // cell owns it); raised cells on it get their flat code back (the descent pass has re-aimed
    // them). A cell's outflow code depends on nothing any path changes, so the marked cells and
    // their codes are the same whatever order the low points are taken in.
    std::size_t mark_outflow(std::size_t p, std::uint64_t* claimed) {
        std::size_t marked = 0;
        for (std::size_t c = p;;) {
            const std::uint64_t bit = std::uint64_t(1) << (c & 63);
            if (std::atomic_ref<std::uint64_t>(claimed[c >> 6]).fetch_or(bit, std::memory_order_relaxed) & bit) break;
            ++marked;
            if (flags[c] & fill_raised) {
                const unsigned set = flat_candidates(filled, g, flags, flat_mask, c);
                dir[c] = std::uint8_t(set & -set);
            }
            if (!dir[c]) break;
            const std::size_t n = d8_target(g, c, dir[c]);
            if (filled[n] < filled[c]) break;
            c = n;
        }
        return marked;
    }

    // mark_outflow from every low point, in parallel chunks, then the marked cells flagged
    // depression_outflow; returns how many.
    std::size_t mark_outflows(const std::vector<std::uint32_t>& low) {
        std::vector<std::uint64_t> claimed((g.size() + 63) / 64, 0);
        std::atomic<std::size_t> marked{0};
        parallel_chunks(low.size(), 1024, [&](std::size_t k0, std::size_t k1) {
            std::size_t n = 0;
            for (std::size_t k = k0; k < k1; ++k) n += mark_outflow(low[k], claimed.data());
            marked += n;
        });
        set_flag_at_bits(claimed, flags.data(), depression_outflow);
        return marked;
    }
};

}  // namespace

void drain_rims_into_depressions(const RoutingGrid& grid, RoutingArrays& arrays) {
    const GridShape& g = grid.shape;
    const std::vector<float>& filled = arrays.z;
    const std::vector<std::uint8_t>& flags = arrays.flags;
    const CellWords& orig_bits = arrays.orig_bits;
    std::vector<std::uint8_t>& dir = arrays.dir;
    const D8Steps st = d8_steps(g, grid.dx, grid.dy);
    auto original = [&](std::size_t n) { return original_z(filled, flags, orig_bits, n); };
    // each rim cell (valid, not raised, next to a raised one) re-aimed once; rows in parallel
    // chunks (a cell writes only its own direction), the tied ones collected in row order
    const std::vector<std::uint32_t> tied = collect_near_raised(
        g, flags, [&](int c, int r, std::size_t x, std::vector<std::uint32_t>& out) {
            if (flags[x] & fill_raised) return;
            const float fx = filled[x];  // = its original elevation
            const D8Choice d = d8_steepest(fx, g, c, r, st, original, [&](std::size_t n) { return filled[n] < fx; });
            dir[x] = d.code();
            if (d.tie()) out.push_back(std::uint32_t(x));
        });
    arrays.ties.insert(arrays.ties.end(), tied.begin(), tied.end());
}

std::size_t drain_depressions(const RoutingGrid& grid, RoutingArrays& arrays, const CellWords& flat_mask) {
    const GridShape& g = grid.shape;
    std::vector<std::uint8_t>& flags = arrays.flags;
    std::vector<std::uint8_t>& dir = arrays.dir;
    Depressions d{arrays.z, flags, arrays.orig_bits, flat_mask, g, d8_steps(g, grid.dx, grid.dy), dir};
    // down the original slopes (cells in parallel chunks: each writes its own direction), low
    // points (first) and tied cells (second) noted in cell order
    const std::vector<std::pair<std::uint32_t, bool>> noted = parallel_collect<std::pair<std::uint32_t, bool>>(
        g.size(), 1 << 16, [&](std::size_t i0, std::size_t i1, std::vector<std::pair<std::uint32_t, bool>>& out) {
            for (std::size_t i = i0; i < i1; ++i) {
                if (!(flags[i] & fill_raised)) continue;
                const D8Choice s = d.descent(i);
                if (!s.steepest) {
                    out.push_back({std::uint32_t(i), true});
                    continue;
                }
                dir[i] = s.code();
                if (s.tie()) out.push_back({std::uint32_t(i), false});
            }
        });
    std::vector<std::uint32_t> low;
    for (const auto& [i, is_low] : noted)
        if (is_low) low.push_back(i);
        else arrays.ties.push_back(i);
    return d.mark_outflows(low);
}

}  // namespace penink
