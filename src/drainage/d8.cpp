#include "drainage/d8.hpp"

#include <cmath>
#include <thread>

namespace penink {

bool is_boundary_cell(const GridShape& g, int c, int r) {
    if (c == 0 || r == 0 || c == g.cols - 1 || r == g.rows - 1) return true;
    const std::size_t i = std::size_t(r) * g.cols + c;
    for (int k = 0; k < 8; ++k)
        if (!g.valid[std::ptrdiff_t(i) + std::ptrdiff_t(d8_dr[k]) * g.cols + d8_dc[k]])
            return true;
    return false;
}

namespace {

struct Steps {
    std::ptrdiff_t off[8];
    float inv[8];  // 1 / distance to neighbour k
};

Steps steps_of(const GridShape& g, double dx, double dy) {
    Steps st{};
    const double diag = std::hypot(dx, dy);
    for (int k = 0; k < 8; ++k) {
        st.off[k] = std::ptrdiff_t(d8_dr[k]) * g.cols + d8_dc[k];
        st.inv[k] = float(1.0 / (d8_dc[k] && d8_dr[k] ? diag : (d8_dc[k] ? dx : dy)));
    }
    return st;
}

// Steepest descent of an interior cell with all 8 neighbours valid: no branches but selects.
inline std::uint8_t steepest_dense(const float* z, std::size_t i, const Steps& st) {
    const float zi = z[i];
    float best = 0.0f;
    unsigned code = 0;
    for (int k = 0; k < 8; ++k) {
        const float s = (zi - z[std::ptrdiff_t(i) + st.off[k]]) * st.inv[k];
        const bool better = s > best;
        best = better ? s : best;
        code = better ? (1u << k) : code;
    }
    return std::uint8_t(code);
}

// Any cell: bounds- and validity-checked. `zn(n)` gives the elevation compared against, `ok(n)`
// whether neighbour n may be a target.
template <class Zn, class Ok>
std::uint8_t steepest_checked(float zi, const GridShape& g, int c, int r, const float* inv,
                              Zn&& zn, Ok&& ok) {
    float best = 0.0f;
    std::uint8_t code = 0;
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
        const std::size_t n = std::size_t(nr) * g.cols + nc;
        if (!g.valid[n] || !ok(n)) continue;
        const float s = (zi - zn(n)) * inv[k];
        if (s > best) best = s, code = std::uint8_t(1u << k);
    }
    return code;
}

void directions_row(const float* z, const GridShape& g, const Steps& st, int r, bool dense,
                    std::uint8_t* dir) {
    const bool edge_row = r == 0 || r == g.rows - 1;
    const std::size_t row0 = std::size_t(r) * g.cols;
    auto checked = [&](int c) {
        const std::size_t i = row0 + c;
        if (!g.valid[i]) return;
        dir[i] = steepest_checked(z[i], g, c, r, st.inv, [&](std::size_t n) { return z[n]; },
                                  [](std::size_t) { return true; });
    };
    if (edge_row || !dense) {
        for (int c = 0; c < g.cols; ++c) checked(c);
        return;
    }
    checked(0);
    for (int c = 1; c + 1 < g.cols; ++c) dir[row0 + c] = steepest_dense(z, row0 + c, st);
    if (g.cols > 1) checked(g.cols - 1);
}

}  // namespace

std::vector<std::uint8_t> d8_directions(const std::vector<float>& z, const GridShape& g,
                                        double dx, double dy) {
    std::vector<std::uint8_t> dir(g.size(), 0);
    const Steps st = steps_of(g, dx, dy);
    bool dense = true;
    for (std::size_t i = 0; i < g.size() && dense; ++i) dense = g.valid[i] != 0;
    // rows are independent: the south half on a second thread (same bytes as one pass)
    const int mid = g.rows / 2;
    std::thread south([&] {
        for (int r = mid; r < g.rows; ++r) directions_row(z.data(), g, st, r, dense, dir.data());
    });
    for (int r = 0; r < mid; ++r) directions_row(z.data(), g, st, r, dense, dir.data());
    south.join();
    return dir;
}

void d8_into_depressions(const std::vector<float>& filled,
                         const std::vector<std::uint8_t>& raised_flags, std::uint8_t bit,
                         const std::vector<std::uint32_t>& orig_bits, const GridShape& g,
                         double dx, double dy, std::vector<std::uint8_t>& dir) {
    const Steps st = steps_of(g, dx, dy);
    auto original = [&](std::size_t n) {
        return raised_flags[n] & bit ? std::bit_cast<float>(orig_bits[n]) : filled[n];
    };
    auto reaim = [&](int c, int r) {
        const std::size_t x = std::size_t(r) * g.cols + c;
        if (!g.valid[x] || (raised_flags[x] & bit)) return;
        const float fx = filled[x];  // = its original elevation
        dir[x] = steepest_checked(fx, g, c, r, st.inv, original,
                                  [&](std::size_t n) { return filled[n] < fx; });
    };
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            if (!(raised_flags[std::size_t(r) * g.cols + c] & bit)) continue;
            for (int k = 0; k < 8; ++k) {
                const int nc = c + d8_dc[k], nr = r + d8_dr[k];
                if (nc >= 0 && nr >= 0 && nc < g.cols && nr < g.rows) reaim(nc, nr);
            }
        }
}

int d8_inflow_count(const std::vector<std::uint8_t>& dir, const GridShape& g, int c, int r) {
    int n = 0;
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
        // the neighbour drains back towards us when its code is the opposite direction (k+4)
        if (dir[std::size_t(nr) * g.cols + nc] == std::uint8_t(1u << ((k + 4) & 7))) ++n;
    }
    return n;
}

std::vector<PointClass> classify_points(const std::vector<std::uint8_t>& dir, const GridShape& g) {
    std::vector<PointClass> cls(g.size(), PointClass::none);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (!g.valid[i]) continue;
            if (dir[i] == 0) { cls[i] = PointClass::pit; continue; }
            const int in = d8_inflow_count(dir, g, c, r);
            cls[i] = in == 0 ? PointClass::ridge : in == 1 ? PointClass::channel : PointClass::junction;
        }
    return cls;
}

}  // namespace penink
