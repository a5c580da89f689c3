// What the fills that flood a grid band by band share (Barnes 2016, "Parallel Priority-Flood
// depression filling for trillion cell digital elevation models", adapted to row bands): a band
// flooded on its own with every cell labelled by the seed it drains to, the spills between
// labels, and the labels' water levels. Used by the in-memory banded fill (banded_fill.hpp) and
// the fill that reads and writes a band at a time (tiled_fill.hpp). Internal to src/drainage.
//
// A band is flooded from the grid's boundary cells in it (label 0, the "ocean") and from every
// valid cell of its first and last rows that is not one already, unless that row is the grid's
// border: such an edge seed takes the label of a neighbour already flooded no higher than itself
// when it leaves the queue, else a new one (labels band_first_label(b, cols) on, in the order they
// leave it; flood.hpp's label_edge: only the edges' local minima start watersheds). Watersheds of
// two labels meet at spills: the higher local level of two 8-adjacent valid cells of different
// labels. Over paths of spills to the ocean, the least highest spill of a label is its water
// level W; a cell's filled level is max(local level, W(label)), the one-thread fill bit for bit.
#pragma once
#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/bit_blocks.hpp"
#include "drainage/priority_flood.hpp"

namespace penink::flood {

// Labels of band b's edge-row seeds start here (at most two rows of cols cells a band).
inline std::uint32_t band_first_label(int b, int cols) { return 1 + std::uint32_t(b) * 2 * std::uint32_t(cols); }
// Label ids of `bands` bands of `cols` columns, the ocean's 0 included.
inline std::size_t band_label_count(int bands, int cols) { return std::size_t(band_first_label(bands, cols)); }

// Floods rows [row0, row1) of g on their own (g may be a window of the grid holding one row more
// on each side where the grid has one: then g's first and last rows are not the grid's border,
// which `top_shared` / `bottom_shared` say): the grid's boundary cells in them, then the edge
// seeds of band b. flags (fill_closed | fill_raised | fill_boundary, band_edge on the edge seeds),
// level (float bits of raised cells) and labels of rows [row0, row1) are set; g's other rows'
// flags must be 0 too (they are never flooded).
FillStats flood_labelled_band(const float* z, const GridShape& g, std::uint8_t* flags, std::uint32_t* level,
                              std::uint32_t* labels, int row0, int row1, bool top_shared, bool bottom_shared, int b);

// Least spill elevation between two labels, keyed (lower label << 32) | higher label.
using Spills = std::unordered_map<std::uint64_t, float>;

inline void note_spill(Spills& s, std::uint32_t a, std::uint32_t b, float w) {
    if (a > b) std::swap(a, b);
    const auto [at, fresh] = s.try_emplace(std::uint64_t(a) << 32 | b, w);
    if (!fresh && w < at->second) at->second = w;
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
        key = ~std::uint64_t(0);
    }
    ~SpillRun() { flush(); }
};

// One row of labelled cells: labels, valid flags and the local level of column c.
template <class Level> struct LabelledRow {
    const std::uint32_t* label;
    const std::uint8_t* valid;
    Level level;
};
template <class Level> LabelledRow(const std::uint32_t*, const std::uint8_t*, Level) -> LabelledRow<Level>;

// The spills from the valid cells of row a to their east neighbour in a and, where the next row
// b is given (has_b), to their south-west, south and south-east neighbours in b. The interior
// cells whose four such neighbours carry their own label (nodata's is 0, like the ocean's) are
// passed over (each_where): a spill needs two labels.
template <class LA, class LB>
void row_pair_spills(int cols, const LabelledRow<LA>& a, const LabelledRow<LB>& b, bool has_b, SpillRun& out) {
    auto cell = [&](int c) {
        if (!a.valid[c]) return;
        const std::uint32_t l = a.label[c];
        if (c + 1 < cols && a.valid[c + 1] && a.label[c + 1] != l) out.note(l, a.label[c + 1], std::max(a.level(c), a.level(c + 1)));
        if (!has_b) return;
        for (int n = std::max(0, c - 1); n <= std::min(cols - 1, c + 1); ++n)
            if (b.valid[n] && b.label[n] != l) out.note(l, b.label[n], std::max(a.level(c), b.level(n)));
    };
    if (!has_b || cols < 3) {
        for (int c = 0; c < cols; ++c) cell(c);
        return;
    }
    const std::uint32_t* l = a.label;
    const std::uint32_t* d = b.label;
    cell(0);
    each_where(
        1, cols - 1, [&](int c) { return (l[c] != l[c + 1]) | (l[c] != d[c - 1]) | (l[c] != d[c]) | (l[c] != d[c + 1]); },
        cell);
    cell(cols - 1);
}

// Water level of every label: over paths of spills to the ocean (label 0), the least highest
// spill (a priority-flood on the label graph); +inf for ids no cell has.
std::vector<float> water_levels(const Spills& spills, std::size_t labels);

// A cell's filled level from its local one and its label's water level (+0.0f: levels come out of
// the queue as +0, never -0, as in the one-thread fill); whether the water raised it.
inline bool raise_to(float local, std::uint32_t label, const std::vector<float>& water, float& filled) {
    if (!label || !(water[label] > local)) return false;
    filled = water[label] + 0.0f;
    return true;
}

}  // namespace penink::flood
