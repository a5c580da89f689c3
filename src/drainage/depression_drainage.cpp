#include "drainage/depression_drainage.hpp"

#include <bit>
#include <vector>

#include "drainage/d8_steepest.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/priority_flood.hpp"

namespace penink {

namespace {

struct Depressions {
    const std::vector<float>& filled;
    std::vector<std::uint8_t>& flags;
    const std::vector<std::uint32_t>& orig;
    const std::vector<std::uint32_t>& flat_mask;
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
    // reaches an outlet or joins a path already marked; raised cells on it get their flat code
    // back (the descent pass has re-aimed them).
    std::size_t mark_outflow(std::size_t p) {
        std::size_t marked = 0;
        for (std::size_t c = p; !(flags[c] & depression_outflow);) {
            flags[c] |= depression_outflow, ++marked;
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
};

}  // namespace

void drain_rims_into_depressions(const std::vector<float>& filled,
                                 const std::vector<std::uint8_t>& flags,
                                 const std::vector<std::uint32_t>& orig_bits, const GridShape& g,
                                 double dx, double dy, std::vector<std::uint8_t>& dir,
                                 std::vector<std::uint32_t>* ties) {
    const D8Steps st = d8_steps(g, dx, dy);
    auto original = [&](std::size_t n) { return original_z(filled, flags, orig_bits, n); };
    auto reaim = [&](int c, int r) {
        const std::size_t x = std::size_t(r) * g.cols + c;
        if (!g.valid[x] || (flags[x] & fill_raised)) return;
        const float fx = filled[x];  // = its original elevation
        const D8Choice d = d8_steepest(fx, g, c, r, st, original,
                                       [&](std::size_t n) { return filled[n] < fx; });
        dir[x] = d.code();
        if (ties && d.tie()) ties->push_back(std::uint32_t(x));
    };
    // each rim cell (not raised, next to a raised one) once: a bit per cell marks those done
    std::vector<std::uint64_t> done((g.size() + 63) / 64, 0);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            if (!(flags[std::size_t(r) * g.cols + c] & fill_raised)) continue;
            for (int k = 0; k < 8; ++k) {
                const int nc = c + d8_dc[k], nr = r + d8_dr[k];
                if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
                const std::size_t n = std::size_t(nr) * g.cols + nc;
                const std::uint64_t bit = std::uint64_t(1) << (n & 63);
                if (done[n >> 6] & bit) continue;
                done[n >> 6] |= bit;
                reaim(nc, nr);
            }
        }
}

std::size_t drain_depressions(const std::vector<float>& filled, std::vector<std::uint8_t>& flags,
                              const std::vector<std::uint32_t>& orig_bits,
                              const std::vector<std::uint32_t>& flat_mask, const GridShape& g,
                              double dx, double dy, std::vector<std::uint8_t>& dir,
                              std::vector<std::uint32_t>* ties) {
    Depressions d{filled, flags, orig_bits, flat_mask, g, d8_steps(g, dx, dy), dir};
    std::vector<std::uint32_t> low;
    for (std::size_t i = 0; i < g.size(); ++i) {  // down the original slopes, low points noted
        if (!(flags[i] & fill_raised)) continue;
        const D8Choice s = d.descent(i);
        if (!s.steepest) { low.push_back(std::uint32_t(i)); continue; }
        dir[i] = s.code();
        if (ties && s.tie()) ties->push_back(std::uint32_t(i));
    }
    std::size_t marked = 0;
    for (const std::uint32_t p : low) marked += d.mark_outflow(p);
    return marked;
}

}  // namespace penink
