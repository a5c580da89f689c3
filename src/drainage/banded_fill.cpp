#include "drainage/banded_fill.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <functional>
#include <limits>
#include <queue>
#include <thread>
#include <unordered_map>
#include <utility>

#include "core/bit_blocks.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/flood.hpp"

namespace penink {

namespace {

// First row of band b of `bands` over `rows` rows (band `bands` starts at `rows`).
int band_row(int b, int bands, int rows) { return int(std::int64_t(rows) * b / bands); }

// Labels of band b's shared-row seeds start here (at most two rows of cols cells a band).
std::uint32_t first_label(int b, int cols) { return 1 + std::uint32_t(b) * 2 * std::uint32_t(cols); }

struct Fill {
    const std::vector<float>& z;
    const GridShape& g;
    std::vector<std::uint8_t>& flags;
    CellWords& level;
    CellWords& labels;
    int bands;

    // The filled level band b's flood gave cell i.
    float local(std::size_t i) const { return flags[i] & fill_raised ? std::bit_cast<float>(level[i]) : z[i]; }
};

// Floods band b on its own: the grid's boundary cells in it (label 0), then the valid cells of the
// rows it shares with its neighbours that are not seeds already (labels from first_label on, in
// cell order).
FillStats flood_band(Fill& s, int b) {
    const GridShape& g = s.g;
    const int r0 = band_row(b, s.bands, g.rows), r1 = band_row(b + 1, s.bands, g.rows);
    flood::Flood f{s.z.data(), g, s.flags.data(), s.level.data(), d8_offsets(g), {}, {}, {}, {}, r0, r1, s.labels.data()};
    flood::seed_band(f);
    std::uint32_t next = first_label(b, g.cols);
    for (const int r : {r0, r1 - 1}) {
        if (r == 0 || r == g.rows - 1) continue;  // the grid's border: seeds already
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (!g.valid[i] || s.flags[i]) continue;
            s.flags[i] = fill_closed | flood::band_edge;
            s.labels[i] = next++;
            f.push_open(std::uint32_t(i));
        }
    }
    flood::run(f);
    return f.stats;
}

// Least spill elevation between two labels, keyed (lower label << 32) | higher label.
using Spills = std::unordered_map<std::uint64_t, float>;

void note_spill(Spills& s, std::uint32_t a, std::uint32_t b, float w) {
    if (a > b) std::swap(a, b);
    const auto [at, fresh] = s.try_emplace(std::uint64_t(a) << 32 | b, w);
    if (!fresh && w < at->second) at->second = w;
}

// Whether row r holds a cell that does not drain to the grid's boundary (nodata is labelled 0).
bool row_has_label(const Fill& s, int r) {
    const std::uint32_t* l = s.labels.data() + std::size_t(r) * s.g.cols;
    std::uint32_t any = 0;
    for (int c = 0; c < s.g.cols; ++c) any |= l[c];
    return any != 0;
}

// Spills noted through the last pair seen: along a watershed boundary the same two labels meet
// cell after cell, so the map is touched once per run of one pair instead of once per cell.
struct SpillRun {
    Spills& out;
    std::uint64_t key = ~std::uint64_t(0);
    float least = 0.0f;
    void note(std::uint32_t a, std::uint32_t b, float w) {
        if (a > b) std::swap(a, b);
        const std::uint64_t k = std::uint64_t(a) << 32 | b;
        if (k == key) {
            least = std::min(least, w);
            return;
        }
        flush();
        key = k, least = w;
    }
    void flush() {
        if (key != ~std::uint64_t(0)) note_spill(out, std::uint32_t(key >> 32), std::uint32_t(key), least);
    }
    ~SpillRun() { flush(); }
};

// The spills from cell (c, r) to its east, south-west, south and south-east neighbours.
void cell_spills(const Fill& s, int c, int r, SpillRun& out) {
    const GridShape& g = s.g;
    const std::size_t i = std::size_t(r) * g.cols + c;
    if (!g.valid[i]) return;
    const int nc[4] = {c + 1, c - 1, c, c + 1}, nr[4] = {r, r + 1, r + 1, r + 1};
    for (int k = 0; k < 4; ++k) {
        if (nc[k] < 0 || nc[k] >= g.cols || nr[k] >= g.rows) continue;
        const std::size_t n = std::size_t(nr[k]) * g.cols + nc[k];
        if (g.valid[n] && s.labels[n] != s.labels[i])
            out.note(s.labels[i], s.labels[n], std::max(s.local(i), s.local(n)));
    }
}

// The spills from the cells of row r (cell_spills). A spill needs two labels, so the interior
// cells whose four neighbours carry their own label (nodata's is 0, like the ocean's) are passed
// over (each_where).
void row_spills(const Fill& s, int r, SpillRun& out) {
    const GridShape& g = s.g;
    if (r + 1 >= g.rows || g.cols < 3) {
        for (int c = 0; c < g.cols; ++c) cell_spills(s, c, r, out);
        return;
    }
    const std::uint32_t* l = s.labels.data() + std::size_t(r) * g.cols;
    const std::uint32_t* d = l + g.cols;
    cell_spills(s, 0, r, out);
    each_where(
        1, g.cols - 1, [&](int c) { return (l[c] != l[c + 1]) | (l[c] != d[c - 1]) | (l[c] != d[c]) | (l[c] != d[c + 1]); },
        [&](int c) { cell_spills(s, c, r, out); });
    cell_spills(s, g.cols - 1, r, out);
}

// Spills between 8-adjacent valid cells of different labels (each pair from its first cell in cell
// order): the higher of their local levels. Rows in parallel chunks (rows r and r + 1 both all
// ocean skipped), the chunks' maps merged.
Spills spill_edges(const Fill& s) {
    const GridShape& g = s.g;
    std::vector<std::uint8_t> labelled(std::size_t(g.rows));
    parallel_chunks(labelled.size(), 64, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t r = r0; r < r1; ++r) labelled[r] = row_has_label(s, int(r));
    });
    const std::size_t per = chunk_length(std::size_t(g.rows), 64);
    std::vector<Spills> part((std::size_t(g.rows) + per - 1) / per);
    parallel_chunks(std::size_t(g.rows), 64, [&](std::size_t r0, std::size_t r1) {
        SpillRun out{part[r0 / per]};
        for (int r = int(r0); r < int(r1); ++r)
            if (labelled[std::size_t(r)] || (r + 1 < g.rows && labelled[std::size_t(r) + 1])) row_spills(s, r, out);
    });
    for (std::size_t k = 1; k < part.size(); ++k)
        for (const auto& [key, w] : part[k]) note_spill(part[0], std::uint32_t(key >> 32), std::uint32_t(key), w);
    return part.empty() ? Spills() : std::move(part[0]);
}

// Water level of every label: over paths of spills to the ocean (label 0), the least highest
// spill (a priority-flood on the label graph); +inf for ids no cell has.
std::vector<float> water_levels(const Spills& spills, std::size_t labels) {
    std::vector<std::vector<std::pair<std::uint32_t, float>>> next(labels);
    for (const auto& [key, w] : spills) {
        const auto a = std::uint32_t(key >> 32), b = std::uint32_t(key);
        next[a].push_back({b, w}), next[b].push_back({a, w});
    }
    std::vector<float> level(labels, std::numeric_limits<float>::infinity());
    using Open = std::pair<float, std::uint32_t>;
    std::priority_queue<Open, std::vector<Open>, std::greater<>> open;
    level[0] = -std::numeric_limits<float>::infinity();
    open.push({level[0], 0});
    while (!open.empty()) {
        const auto [h, l] = open.top();
        open.pop();
        if (h > level[l]) continue;  // reached lower since
        for (const auto& [m, w] : next[l])
            if (const float hm = std::max(h, w); hm < level[m]) level[m] = hm, open.push({hm, m});
    }
    return level;
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
            const std::uint32_t l = s.labels[i];
            if (!l || !(water[l] > s.local(i))) continue;
            n += (s.flags[i] & fill_raised) == 0;
            s.level[i] = std::bit_cast<std::uint32_t>(water[l] + 0.0f), s.flags[i] |= fill_raised;
        }
        raised += n;
    });
    return raised;
}

}  // namespace

int fill_bands(int rows) {
    const int threads = int(std::clamp<unsigned>(std::thread::hardware_concurrency(), 1, 16));
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
    st.raised += raise_to_water(s, water_levels(spill_edges(s), first_label(bands, g.cols)));
    return st;
}

}  // namespace penink
