// The steepest-descent choice shared by the D8 stages (d8.cpp, depression_drainage.cpp,
// d8_ties.cpp): per-neighbour offsets and inverse distances (metres) of a grid, and the steepest
// admissible neighbour of one cell with a flag telling whether another neighbour ties with it
// exactly (same float drop / distance), so a later pass can break the tie (d8_ties.hpp).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "drainage/d8.hpp"

namespace penink {

struct D8Steps {
    std::ptrdiff_t off[8];  // linear index offset of neighbour k
    float inv[8];           // 1 / distance to neighbour k (cardinal dx or dy, diagonal hypot)
};

inline D8Steps d8_steps(const GridShape& g, double dx, double dy) {
    D8Steps st{};
    const double diag = std::hypot(dx, dy);
    for (int k = 0; k < 8; ++k) {
        st.off[k] = std::ptrdiff_t(d8_dr[k]) * g.cols + d8_dc[k];
        st.inv[k] = float(1.0 / (d8_dc[k] && d8_dr[k] ? diag : (d8_dc[k] ? dx : dy)));
    }
    return st;
}

struct D8Choice {
    std::uint8_t code = 0;  // ESRI code of the steepest neighbour (lowest code on ties), 0 = none
    bool tie = false;       // another admissible neighbour has exactly the same slope
};

// Steepest strictly-downhill neighbour of valid cell (c, r) at elevation zi: bounds- and
// validity-checked; `zn(n)` gives the elevation compared against, `ok(n)` whether neighbour n
// may be a target at all.
template <class Zn, class Ok>
D8Choice d8_steepest(float zi, const GridShape& g, int c, int r, const D8Steps& st, Zn&& zn, Ok&& ok) {
    D8Choice out;
    float best = 0.0f;
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
        const std::size_t n = std::size_t(nr) * g.cols + nc;
        if (!g.valid[n] || !ok(n)) continue;
        const float s = (zi - zn(n)) * st.inv[k];
        if (s > best) best = s, out.code = std::uint8_t(1u << k), out.tie = false;
        else if (s == best && out.code) out.tie = true;
    }
    return out;
}

}  // namespace penink
