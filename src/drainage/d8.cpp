#include "drainage/d8.hpp"

#include "core/parallel_chunks.hpp"
#include "drainage/d8_steepest.hpp"

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

// Cells [i0, i1) whose 3x3 blocks are all data: code and tie flag of each (d8_steepest_dense),
// written for a whole run at once so the compiler vectorises across cells (a base pointer per
// neighbour, restrict: the byte stores alias nothing the loop reads).
void dense_run(const float* __restrict z, std::size_t i0, std::size_t i1, const D8Steps& st,
               std::uint8_t* __restrict dir, std::uint8_t* __restrict tie) {
    const float* zk[8];
    float inv[8];
    for (int k = 0; k < 8; ++k) zk[k] = z + st.off[k], inv[k] = st.inv[k];
    for (std::size_t i = i0; i < i1; ++i) {
        const float zi = z[i];
        float best = 0.0f;
        unsigned set = 0;
#pragma GCC unroll 8
        for (int k = 0; k < 8; ++k) d8_take((zi - zk[k][i]) * inv[k], k, best, set);
        set = best > 0.0f ? set : 0u;
        dir[i] = std::uint8_t(set & -set);
        tie[i - i0] = (set & (set - 1)) != 0;
    }
}

void directions_row(const float* z, const GridShape& g, const D8Steps& st, int r, bool dense,
                    std::uint8_t* dir, std::vector<std::uint32_t>* ties, std::vector<std::uint8_t>& tie) {
    const std::size_t row0 = std::size_t(r) * g.cols;
    tie.resize(std::size_t(g.cols));
    dense_runs(
        g, r, dense,
        [&](std::size_t i0, std::size_t i1) {  // ties in cell order
            dense_run(z, i0, i1, st, dir, tie.data());
            if (ties)
                for (std::size_t i = i0; i < i1; ++i)
                    if (tie[i - i0]) ties->push_back(std::uint32_t(i));
        },
        [&](int c) {
            const std::size_t i = row0 + c;
            if (!g.valid[i]) return;
            const D8Choice d = d8_steepest(z[i], g, c, r, st, [&](std::size_t n) { return z[n]; },
                                           [](std::size_t) { return true; });
            dir[i] = d.code();
            if (ties && d.tie()) ties->push_back(std::uint32_t(i));
        });
}

}  // namespace

std::vector<std::uint8_t> d8_directions(const std::vector<float>& z, const GridShape& g,
                                        double dx, double dy, std::vector<std::uint32_t>* ties,
                                        bool two_threads) {
    std::vector<std::uint8_t> dir(g.size(), 0);
    const D8Steps st = d8_steps(g, dx, dy);
    const bool dense = all_valid(g);
    // rows are independent: the south half on a second thread (same bytes as one pass)
    const int mid = two_threads ? g.rows / 2 : g.rows;
    std::vector<std::uint32_t> south_ties;
    const auto rows = [&](int r0, int r1, std::vector<std::uint32_t>* out) {
        std::vector<std::uint8_t> tie;
        for (int r = r0; r < r1; ++r) directions_row(z.data(), g, st, r, dense, dir.data(), out, tie);
    };
    if (mid < g.rows)
        run_beside([&] { rows(mid, g.rows, ties ? &south_ties : nullptr); }, [&] { rows(0, mid, ties); });
    else
        rows(0, g.rows, ties);
    if (ties) ties->insert(ties->end(), south_ties.begin(), south_ties.end());
    return dir;
}

}  // namespace penink
