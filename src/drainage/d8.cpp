#include "drainage/d8.hpp"

#include <cmath>

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

// Steepest descent of an interior cell (all 8 neighbours in the grid): no bounds checks.
std::uint8_t steepest_interior(const float* z, const std::uint8_t* valid, std::size_t i,
                               const std::ptrdiff_t* off, const float* inv_dist) {
    const float zi = z[i];
    float best = 0.0f;
    std::uint8_t code = 0;
    for (int k = 0; k < 8; ++k) {
        const std::size_t n = std::size_t(std::ptrdiff_t(i) + off[k]);
        const float s = (zi - z[n]) * inv_dist[k];
        if (s > best && valid[n]) best = s, code = std::uint8_t(1u << k);
    }
    return code;
}

std::uint8_t steepest_checked(const float* z, const GridShape& g, int c, int r,
                              const float* inv_dist) {
    const std::size_t i = std::size_t(r) * g.cols + c;
    float best = 0.0f;
    std::uint8_t code = 0;
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
        const std::size_t n = std::size_t(nr) * g.cols + nc;
        const float s = (z[i] - z[n]) * inv_dist[k];
        if (s > best && g.valid[n]) best = s, code = std::uint8_t(1u << k);
    }
    return code;
}

}  // namespace

std::vector<std::uint8_t> d8_directions(const std::vector<float>& z, const GridShape& g,
                                        double dx, double dy) {
    std::vector<std::uint8_t> dir(g.size(), 0);
    std::ptrdiff_t off[8];
    float inv[8];
    const double diag = std::hypot(dx, dy);
    for (int k = 0; k < 8; ++k) {
        off[k] = std::ptrdiff_t(d8_dr[k]) * g.cols + d8_dc[k];
        inv[k] = float(1.0 / (d8_dc[k] && d8_dr[k] ? diag : (d8_dc[k] ? dx : dy)));
    }
    for (int r = 0; r < g.rows; ++r) {
        const bool edge_row = r == 0 || r == g.rows - 1;
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (!g.valid[i]) continue;
            const bool edge = edge_row || c == 0 || c == g.cols - 1;
            dir[i] = edge ? steepest_checked(z.data(), g, c, r, inv)
                          : steepest_interior(z.data(), g.valid, i, off, inv);
        }
    }
    return dir;
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
