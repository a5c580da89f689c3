#include "drainage/depression_drainage.hpp"

#include <bit>

#include "drainage/d8_steepest.hpp"
#include "drainage/priority_flood.hpp"

namespace penink {

namespace {

struct Depressions {
    const std::vector<float>& filled;
    std::vector<std::uint8_t>& flags;
    const std::vector<std::uint32_t>& orig;
    const GridShape& g;
    D8Steps st;
    std::vector<std::uint8_t>& dir;

    float original(std::size_t n) const { return original_z(filled, flags, orig, n); }
    bool raised(std::size_t i) const { return g.valid[i] && (flags[i] & fill_raised); }

    // Steepest descent of raised cell (c, r) on the original elevations.
    D8Choice descent(int c, int r) const {
        const std::size_t i = std::size_t(r) * g.cols + c;
        const float zi = original(i);
        return d8_steepest(zi, g, c, r, st, [&](std::size_t n) { return original(n); },
                           [&](std::size_t n) { return original(n) < zi; });
    }

    // Marks the flat-resolved path from low point p until it steps down off the filled flat,
    // reaches an outlet or joins a path already marked.
    std::size_t mark_outflow(std::size_t p) {
        std::size_t marked = 0;
        for (std::size_t c = p; !(flags[c] & depression_outflow);) {
            flags[c] |= depression_outflow, ++marked;
            if (!dir[c]) break;
            const std::size_t n = d8_target(g, c, dir[c]);
            if (filled[n] < filled[c]) break;
            c = n;
        }
        return marked;
    }
};

}  // namespace

std::size_t drain_depressions(const std::vector<float>& filled, std::vector<std::uint8_t>& flags,
                              const std::vector<std::uint32_t>& orig_bits, const GridShape& g,
                              double dx, double dy, std::vector<std::uint8_t>& dir,
                              std::vector<std::uint32_t>* ties) {
    Depressions d{filled, flags, orig_bits, g, d8_steps(g, dx, dy), dir};
    std::size_t marked = 0;
    for (int r = 0; r < g.rows; ++r)  // the low points' outflow paths first, on flat directions
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (d.raised(i) && !(flags[i] & depression_outflow) && !d.descent(c, r).code)
                marked += d.mark_outflow(i);
        }
    for (int r = 0; r < g.rows; ++r)  // then everything else down the original slopes
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (!d.raised(i) || (flags[i] & depression_outflow)) continue;
            const D8Choice s = d.descent(c, r);
            dir[i] = s.code;
            if (s.tie && ties) ties->push_back(std::uint32_t(i));
        }
    return marked;
}

}  // namespace penink
