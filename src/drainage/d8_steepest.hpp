// The steepest-descent choice shared by the D8 stages (d8.cpp, depression_drainage.cpp,
// d8_ties.cpp): per-neighbour offsets and inverse distances (metres) of a grid, and the set of
// admissible neighbours of one cell with exactly the steepest drop / distance (float), whose
// lowest code is the D8 direction; a set of two or more is a tie for d8_ties.hpp.
#pragma once
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "drainage/d8.hpp"

namespace penink {

struct D8Steps {
    std::array<std::ptrdiff_t, 8> off;  // linear index offset of neighbour k (d8_offsets)
    float inv[8];           // 1 / distance to neighbour k (cardinal dx or dy, diagonal hypot)
};

inline D8Steps d8_steps(const GridShape& g, double dx, double dy) {
    D8Steps st{d8_offsets(g), {}};
    const double diag = std::hypot(dx, dy);
    for (int k = 0; k < 8; ++k)
        st.inv[k] = float(1.0 / (d8_dc[k] && d8_dr[k] ? diag : (d8_dc[k] ? dx : dy)));
    return st;
}

struct D8Choice {
    unsigned steepest = 0;  // bit k for every admissible neighbour k of the steepest slope (> 0)
    std::uint8_t code() const { return std::uint8_t(steepest & -steepest); }  // lowest; 0 = none
    bool tie() const { return (steepest & (steepest - 1)) != 0; }  // two or more bits
};

// Takes slope s to neighbour k into the running maximum `best` and its set (no branches).
inline void d8_take(float s, int k, float& best, unsigned& set) {
    const bool better = s > best;
    set = better ? 1u << k : (s == best ? set | 1u << k : set);
    best = better ? s : best;
}

// Steepest strictly-downhill neighbours of cell i at elevation zi when all 8 neighbours exist
// and are admissible (an interior cell, no nodata around); `zn(n)` gives neighbour n's elevation.
template <class Zn>
D8Choice d8_steepest_dense(float zi, std::size_t i, const D8Steps& st, Zn&& zn) {
    float best = 0.0f;
    unsigned set = 0;
    for (int k = 0; k < 8; ++k)
        d8_take((zi - zn(std::size_t(std::ptrdiff_t(i) + st.off[k]))) * st.inv[k], k, best, set);
    return {best > 0.0f ? set : 0u};
}

// The same for any valid cell (c, r): bounds- and validity-checked; `ok(n)` tells whether
// neighbour n may be a target at all.
template <class Zn, class Ok>
D8Choice d8_steepest(float zi, const GridShape& g, int c, int r, const D8Steps& st, Zn&& zn, Ok&& ok) {
    float best = 0.0f;
    unsigned set = 0;
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
        const std::size_t n = std::size_t(nr) * g.cols + nc;
        if (g.valid[n] && ok(n)) d8_take((zi - zn(n)) * st.inv[k], k, best, set);
    }
    return {best > 0.0f ? set : 0u};
}

// Row r of the grid split, in column order, into maximal runs of interior cells whose 3x3 block
// is all data (run(i0, i1): cell indices) and the other cells (single(c)); `all_valid`: the grid
// has no nodata (no per-cell test). The runs are what the vectorised kernels take.
template <class Run, class Single>
void dense_runs(const GridShape& g, int r, bool all_valid, Run&& run, Single&& single) {
    const std::size_t row0 = std::size_t(r) * g.cols;
    if (r == 0 || r == g.rows - 1 || g.cols < 3) {
        for (int c = 0; c < g.cols; ++c) single(c);
        return;
    }
    single(0);
    std::size_t start = row0 + 1;
    if (!all_valid) {
        const std::uint8_t* v = g.valid;
        for (std::size_t i = row0 + 1; i + 1 < row0 + g.cols; ++i) {
            const std::size_t n = i - g.cols, s = i + g.cols;
            if (v[n - 1] & v[n] & v[n + 1] & v[i - 1] & v[i] & v[i + 1] & v[s - 1] & v[s] & v[s + 1]) continue;
            if (start < i) run(start, i);
            single(int(i - row0));
            start = i + 1;
        }
    }
    if (start < row0 + g.cols - 1) run(start, row0 + g.cols - 1);
    single(g.cols - 1);
}

// Whether the grid has no nodata cell.
inline bool all_valid(const GridShape& g) {
    for (std::size_t i = 0; i < g.size(); ++i)
        if (!g.valid[i]) return false;
    return true;
}

}  // namespace penink
