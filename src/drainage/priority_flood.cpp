#include "drainage/priority_flood.hpp"

#include <algorithm>
#include <bit>

#include "core/parallel_chunks.hpp"
#include "drainage/flood.hpp"

namespace penink {

FillStats priority_flood_levels(const std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                                CellWords& level_bits) {
    flags.assign(g.size(), 0);
    level_bits.resize(g.size());
    flood::Flood f{z.data(), g, flags.data(), level_bits.data(), d8_offsets(g), {}, {}, {}, {}, 0, g.rows, nullptr};
    flood::seed_band(f);
    flood::run(f);
    return f.stats;
}

bool next_to_raised(const GridShape& g, const std::vector<std::uint8_t>& flags, int c, int r) {
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc >= 0 && nr >= 0 && nc < g.cols && nr < g.rows && (flags[std::size_t(nr) * g.cols + nc] & fill_raised))
            return true;
    }
    return false;
}

// column[c]: the raised bit of rows r-1..r+1 in column c, then spread to columns c-1..c+1
// (plain byte loops the compiler vectorises).
void near_raised_row(const GridShape& g, const std::vector<std::uint8_t>& flags, int r,
                     std::vector<std::uint8_t>& column, std::uint8_t* near) {
    const std::size_t w = std::size_t(g.cols);
    const std::uint8_t* row = flags.data() + std::size_t(r) * w;
    const std::uint8_t* above = r > 0 ? row - w : row;
    const std::uint8_t* below = r + 1 < g.rows ? row + w : row;
    column.resize(w + 2);
    column[0] = column[w + 1] = 0;
    for (std::size_t c = 0; c < w; ++c) column[c + 1] = (above[c] | row[c] | below[c]) & fill_raised;
    for (std::size_t c = 0; c < w; ++c) near[c] = column[c] | column[c + 1] | column[c + 2];
}

void swap_raised(std::vector<float>& z, const std::vector<std::uint8_t>& flags, CellWords& bits) {
    parallel_chunks(z.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i)
            if (flags[i] & fill_raised) {
                const std::uint32_t zi = std::bit_cast<std::uint32_t>(z[i]);
                z[i] = std::bit_cast<float>(bits[i]), bits[i] = zi;
            }
    });
}

FillStats priority_flood_fill(std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                              CellWords& orig_bits) {
    const FillStats st = priority_flood_levels(z, g, flags, orig_bits);
    swap_raised(z, flags, orig_bits);
    return st;
}

}  // namespace penink
