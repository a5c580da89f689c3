#include "drainage/fill_directions.hpp"

#include <algorithm>
#include <bit>
#include <exception>
#include <thread>

#include "core/parallel_chunks.hpp"
#include "drainage/d8_steepest.hpp"

namespace penink {

namespace {

// One bit per cell: the cells whose 3x3 block holds a raised cell.
std::vector<std::uint64_t> near_raised(const GridShape& g, const std::vector<std::uint8_t>& flags) {
    std::vector<std::uint64_t> bits((g.size() + 63) / 64, 0);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            if (!(flags[std::size_t(r) * g.cols + c] & fill_raised)) continue;
            for (int nr = std::max(r - 1, 0); nr <= std::min(r + 1, g.rows - 1); ++nr)
                for (int nc = std::max(c - 1, 0); nc <= std::min(c + 1, g.cols - 1); ++nc) {
                    const std::size_t n = std::size_t(nr) * g.cols + nc;
                    bits[n >> 6] |= std::uint64_t(1) << (n & 63);
                }
        }
    return bits;
}

bool marked(const std::vector<std::uint64_t>& bits, std::size_t i) { return bits[i >> 6] >> (i & 63) & 1; }

// Directions (and ties) of the marked cells taken again on z, the filled surface.
void redo_marked(const std::vector<float>& z, const GridShape& g, double dx, double dy,
                 const std::vector<std::uint64_t>& bits, std::vector<std::uint8_t>& dir,
                 std::vector<std::uint32_t>& ties) {
    std::erase_if(ties, [&](std::uint32_t i) { return marked(bits, i); });
    const D8Steps st = d8_steps(g, dx, dy);
    auto zn = [&](std::size_t n) { return z[n]; };
    for (std::size_t w = 0; w < bits.size(); ++w)
        for (std::uint64_t b = bits[w]; b; b &= b - 1) {
            const std::size_t i = w * 64 + std::size_t(std::countr_zero(b));
            if (!g.valid[i]) continue;
            const D8Choice d = d8_steepest(z[i], g, int(i % std::size_t(g.cols)), int(i / std::size_t(g.cols)),
                                           st, zn, [](std::size_t) { return true; });
            dir[i] = d.code();
            if (d.tie()) ties.push_back(std::uint32_t(i));
        }
}

}  // namespace

FillStats fill_with_directions(std::vector<float>& z, const GridShape& g, double dx, double dy,
                               std::vector<std::uint8_t>& flags, std::vector<std::uint32_t>& orig_bits,
                               std::vector<std::uint8_t>& dir, std::vector<std::uint32_t>& ties) {
    FillStats st;
    run_beside([&] { dir = d8_directions(z, g, dx, dy, &ties, false); },  // reads z and g only, like the fill
               [&] { st = priority_flood_levels(z, g, flags, orig_bits); });
    swap_raised(z, flags, orig_bits);
    redo_marked(z, g, dx, dy, near_raised(g, flags), dir, ties);
    return st;
}

}  // namespace penink
