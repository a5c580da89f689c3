#include "drainage/banded_fill.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <thread>
#include <utility>

#include "core/parallel_chunks.hpp"
#include "drainage/band_flood.hpp"
#include "drainage/flood.hpp"

namespace penink {

namespace {

// First row of band b of `bands` over `rows` rows (band `bands` starts at `rows`).
int band_row(int b, int bands, int rows) { return int(std::int64_t(rows) * b / bands); }

struct Fill {
    const std::vector<float>& z;
    const GridShape& g;
    std::vector<std::uint8_t>& flags;
    CellWords& level;
    CellWords& labels;
    int bands;

    // The filled level band b's flood gave cell i.
    float local(std::size_t i) const { return flags[i] & fill_raised ? std::bit_cast<float>(level[i]) : z[i]; }
    // Row r's labels, valid flags and local levels.
    auto row(int r) const {
        const std::size_t at = std::size_t(r) * g.cols;
        return flood::LabelledRow{labels.data() + at, g.valid + at, [this, at](int c) { return local(at + std::size_t(c)); }};
    }
};

// Floods band b on its own (flood::flood_labelled_band on the whole grid, its rows alone).
FillStats flood_band(Fill& s, int b) {
    const GridShape& g = s.g;
    const int r0 = band_row(b, s.bands, g.rows), r1 = band_row(b + 1, s.bands, g.rows);
    return flood::flood_labelled_band(s.z.data(), g, s.flags.data(), s.level.data(), s.labels.data(), r0, r1, r0 > 0,
                                      r1 < g.rows, b);
}

// Whether row r holds a cell that does not drain to the grid's boundary (nodata is labelled 0).
bool row_has_label(const Fill& s, int r) {
    const std::uint32_t* l = s.labels.data() + std::size_t(r) * s.g.cols;
    std::uint32_t any = 0;
    for (int c = 0; c < s.g.cols; ++c) any |= l[c];
    return any != 0;
}

// Spills between 8-adjacent valid cells of different labels (each pair from its first cell in cell
// order): the higher of their local levels. Rows in parallel chunks (rows r and r + 1 both all
// ocean skipped), the chunks' maps merged.
flood::Spills spill_edges(const Fill& s) {
    const GridShape& g = s.g;
    std::vector<std::uint8_t> labelled(std::size_t(g.rows));
    parallel_chunks(labelled.size(), 64, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t r = r0; r < r1; ++r) labelled[r] = row_has_label(s, int(r));
    });
    const std::size_t per = chunk_length(std::size_t(g.rows), 64);
    std::vector<flood::Spills> part((std::size_t(g.rows) + per - 1) / per);
    parallel_chunks(std::size_t(g.rows), 64, [&](std::size_t r0, std::size_t r1) {
        flood::SpillRun out{part[r0 / per]};
        for (int r = int(r0); r < int(r1); ++r)
            if (labelled[std::size_t(r)] || (r + 1 < g.rows && labelled[std::size_t(r) + 1])) {
                const bool next = r + 1 < g.rows;
                flood::row_pair_spills(g.cols, s.row(r), s.row(next ? r + 1 : r), next, out);
            }
    });
    for (std::size_t k = 1; k < part.size(); ++k)
        for (const auto& [key, w] : part[k]) flood::note_spill(part[0], std::uint32_t(key >> 32), std::uint32_t(key), w);
    return part.empty() ? flood::Spills() : std::move(part[0]);
}

// Every labelled cell raised to its label's water level where that is above its local level
// (+0.0f: levels come out of the queue as +0, never -0, as in the one-thread fill), cells of label
// 0 (the grid's boundary's and nodata) passed over at once; the band-edge marks cleared (they lie
// on the bands' first and last rows). Returns how many cells it raised that their band had not.
std::size_t raise_to_water(Fill& s, const std::vector<float>& water) {
    const GridShape& g = s.g;
    for (int b = 0; b < s.bands; ++b)
        for (const int r : {band_row(b, s.bands, g.rows), band_row(b + 1, s.bands, g.rows) - 1})
            for (std::size_t i = std::size_t(r) * g.cols; i < std::size_t(r + 1) * g.cols; ++i)
                s.flags[i] &= std::uint8_t(~flood::band_edge);
    std::atomic<std::size_t> raised{0};
    parallel_chunks(g.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1) {
        std::size_t n = 0;
        for (std::size_t i = i0; i < i1; ++i) {
            float filled;
            if (!flood::raise_to(s.local(i), s.labels[i], water, filled)) continue;
            n += (s.flags[i] & fill_raised) == 0;
            s.level[i] = std::bit_cast<std::uint32_t>(filled), s.flags[i] |= fill_raised;
        }
        raised += n;
    });
    return raised;
}

}  // namespace

int fill_bands(int rows) {
    const int threads = int(core_count());
    return std::max(1, std::min(threads, rows / 256));
}

FillStats priority_flood_levels_banded(const std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                                       CellWords& level_bits, CellWords& labels,
                                       int bands) {
    bands = std::clamp(bands, 1, std::max(1, g.rows / 2));
    if (bands == 1) return priority_flood_levels(z, g, flags, level_bits);
    flags.assign(g.size(), 0);
    level_bits.resize(g.size());
    labels.resize(g.size());
    Fill s{z, g, flags, level_bits, labels, bands};
    std::vector<FillStats> band(std::size_t(bands), FillStats{});
    parallel_chunks(band.size(), 1, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b) band[b] = flood_band(s, int(b));
    });
    FillStats st;
    for (const FillStats& b : band) st.queued += b.queued, st.raised += b.raised;
    st.raised += raise_to_water(s, flood::water_levels(spill_edges(s), flood::band_label_count(bands, g.cols)));
    return st;
}

}  // namespace penink
