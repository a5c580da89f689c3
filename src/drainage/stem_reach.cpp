#include "drainage/stem_reach.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/block_codec.hpp"
#include "core/parallel_chunks.hpp"

namespace penink {

CellBox stem_cell_reach(const std::uint32_t* cells, std::uint32_t n, const DrainageGrid& g, const FallLineOptions& options) {
    CellBox b;
    if (n == 0 || g.cols < 1) return b;
    const auto cols = std::uint32_t(g.cols);
    auto at = [&](std::uint32_t k) { return glm::dvec2(double(cells[k] % cols), double(cells[k] / cols)); };
    glm::dvec2 lo = at(0), hi = lo;
    auto add = [&](glm::dvec2 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); };
    for (std::uint32_t k = 1; k < n; ++k) add(at(k));
    // the reflections through the ends within the kernel's radius (GaussianKernel: ceil(3 sigma))
    const auto radius = std::uint32_t(std::ceil(3.0 * options.sigma));
    for (std::uint32_t m = 1; m <= radius && m < n; ++m) add(2.0 * at(0) - at(m)), add(2.0 * at(n - 1) - at(n - 1 - m));
    const double grow = options.max_corridor + 1.0;
    b.c0 = std::max(0.0, lo.x - grow), b.r0 = std::max(0.0, lo.y - grow);
    b.c1 = std::min(double(g.cols - 1), hi.x + grow), b.r1 = std::min(double(g.rows - 1), hi.y + grow);
    return b;
}

StemTravel stem_cell_travel(const std::uint32_t* cells, std::uint32_t n, const DrainageGrid& g, const glm::vec2* xy) {
    const auto cols = std::uint32_t(g.cols);
    const glm::vec2* given = g.factor == 1 ? xy : nullptr;
    auto at = [&](std::uint32_t k) {
        const glm::dvec2 p = given ? glm::dvec2(given[k]) : grid_xy(g, int(cells[k] % cols), int(cells[k] / cols));
        return glm::dvec3(p, double(g.z[cells[k]]));
    };
    StemTravel t;
    glm::dvec3 last = n ? at(0) : glm::dvec3(0.0);
    for (std::uint32_t k = 1; k < n; ++k) {
        const glm::dvec3 p = at(k);
        t.plan += glm::length(glm::dvec2(p) - glm::dvec2(last)), t.rise += std::abs(p.z - last.z), last = p;
    }
    return t;
}

namespace {

// std::nextafter(f, INFINITY) and (f, -INFINITY), the same floats by the bits (the library call
// is most of a bound's time, millions of stems in an index).
float float_up(float f) {
    if (!(f < INFINITY)) return f;  // NaN, +inf
    if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(f);
    return std::bit_cast<float>(bits >> 31 ? bits - 1 : bits + 1);
}
float float_down(float f) { return -float_up(-f); }

constexpr double bound_steps = 65535.0;

// The plan coordinate of step q across [lo, hi], rounded to a float downward (or upward).
float step_value(std::uint16_t q, float lo, float hi, bool up) {
    const double v = double(lo) + (double(hi) - double(lo)) * (double(q) / bound_steps);
    const float f = float(v);
    if (up) return double(f) < v ? float_up(f) : f;
    return double(f) > v ? float_down(f) : f;
}

// The last step whose value (rounded down) is at most v, or (up) the first whose value (rounded
// up) is at least v; 0 or 65535 beyond [lo, hi].
std::uint16_t step_of(float v, float lo, float hi, bool up) {
    if (!(hi > lo)) return up ? std::uint16_t(65535) : std::uint16_t(0);
    const double t = std::clamp((double(v) - double(lo)) / (double(hi) - double(lo)) * bound_steps, 0.0, bound_steps);
    int q = int(up ? std::ceil(t) : std::floor(t));
    if (up)
        while (q < 65535 && step_value(std::uint16_t(q), lo, hi, true) < v) ++q;
    else
        while (q > 0 && step_value(std::uint16_t(q), lo, hi, false) > v) --q;
    return std::uint16_t(q);
}

// The high half of the float at or above v, rounded up (a bfloat16 at or above v).
std::uint16_t bfloat_up(double v) {
    float f = float(v);
    if (double(f) < v) f = float_up(f);
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    if (bits & 0xffffu) bits += 0x10000u;
    return std::uint16_t(bits >> 16);
}
float bfloat_value(std::uint16_t h) {
    const std::uint32_t bits = std::uint32_t(h) << 16;
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

constexpr int bound_fields = 6;  // x0, y0, x1 - x0, y1 - y0, plan, rise
}  // namespace

StemBound stem_bound(glm::vec2 reach_lo, glm::vec2 reach_hi, StemTravel t, glm::vec2 lo, glm::vec2 hi) {
    StemBound b;
    const glm::vec2 l = glm::max(reach_lo, lo), h = glm::min(reach_hi, hi);
    if (l.x <= h.x && l.y <= h.y)
        b.x0 = step_of(l.x, lo.x, hi.x, false), b.y0 = step_of(l.y, lo.y, hi.y, false),
        b.x1 = step_of(h.x, lo.x, hi.x, true), b.y1 = step_of(h.y, lo.y, hi.y, true);
    b.plan = bfloat_up(crease_length_factor * t.plan);
    b.rise = bfloat_up(crease_rise_factor * (t.rise + crease_rise_slope * t.plan));
    return b;
}

StemBound stem_line_bound(glm::vec2 box_lo, glm::vec2 box_hi, StemTravel t, const StemBound& reach, glm::vec2 lo,
                          glm::vec2 hi) {
    StemBound b;
    if (box_lo.x <= box_hi.x && box_lo.y <= box_hi.y)
        b.x0 = std::max(reach.x0, step_of(box_lo.x, lo.x, hi.x, false)),
        b.y0 = std::max(reach.y0, step_of(box_lo.y, lo.y, hi.y, false)),
        b.x1 = std::min(reach.x1, step_of(box_hi.x, lo.x, hi.x, true)),
        b.y1 = std::min(reach.y1, step_of(box_hi.y, lo.y, hi.y, true));
    // (bfloat16 bits order as their values: non-negative)
    b.plan = std::min(reach.plan, bfloat_up(t.plan)), b.rise = std::min(reach.rise, bfloat_up(t.rise));
    return b;
}

void stem_bound_box(const StemBound& b, glm::vec2 lo, glm::vec2 hi, glm::vec2& box_lo, glm::vec2& box_hi) {
    if (b.x1 < b.x0 || b.y1 < b.y0) {
        box_lo = glm::vec2(std::numeric_limits<float>::infinity()), box_hi = -box_lo;
        return;
    }
    box_lo = {step_value(b.x0, lo.x, hi.x, false), step_value(b.y0, lo.y, hi.y, false)};
    box_hi = {step_value(b.x1, lo.x, hi.x, true), step_value(b.y1, lo.y, hi.y, true)};
}

float stem_bound_plan(const StemBound& b) { return bfloat_value(b.plan); }
float stem_bound_rise(const StemBound& b) { return bfloat_value(b.rise); }
double stem_bound_length(const StemBound& b, double e) {
    return double(stem_bound_plan(b)) + std::max(0.0, e) * double(stem_bound_rise(b));
}

float drape_height_top(const DrainageGrid& g) {
    const bool coarse = g.factor > 1 && !g.coarse_z.empty();
    const int cols = coarse ? g.coarse_cols : g.cols, rows = coarse ? g.coarse_rows : g.rows;
    const std::vector<float>& z = coarse ? g.coarse_z : g.z;
    const std::vector<std::uint8_t>& valid = coarse ? g.coarse_valid : g.valid;
    // the nodes of row r (x, y as the drape reads them, z) into `out`
    auto row_nodes = [&](int r, std::vector<glm::dvec3>& out) {
        out.resize(std::size_t(cols));
        for (int c = 0; c < cols; ++c) {
            const std::size_t i = std::size_t(r) * std::size_t(cols) + std::size_t(c);
            const glm::dvec2 xy = coarse ? glm::dvec2(g.coarse_xy[i]) : grid_xy(g, c, r);
            out[std::size_t(c)] = glm::dvec3(xy, double(z[i]));
        }
    };
    // per row on all cores (the highest node and the longest squared edge down to the next row),
    // each row's nodes found once
    std::vector<double> row_top(std::size_t(std::max(rows, 0)), -std::numeric_limits<double>::infinity());
    std::vector<double> row_edge2(row_top.size(), 0.0);
    parallel_chunks(row_top.size(), 16, [&](std::size_t r0, std::size_t r1) {
        std::vector<glm::dvec3> here, below;
        if (r0 < r1) row_nodes(int(r0), here);
        for (int r = int(r0); r < int(r1); ++r) {
            if (r + 1 < rows) row_nodes(r + 1, below);
            for (int c = 0; c < cols; ++c) {
                const std::size_t i = std::size_t(r) * std::size_t(cols) + std::size_t(c);
                if (!valid[i]) continue;
                const glm::dvec3 p = here[std::size_t(c)];
                row_top[std::size_t(r)] = std::max(row_top[std::size_t(r)], p.z);
                for (const auto& [dc, dr] : {std::pair(1, 0), std::pair(0, 1), std::pair(1, 1)}) {
                    if (c + dc >= cols || r + dr >= rows || !valid[i + std::size_t(dr) * std::size_t(cols) + std::size_t(dc)])
                        continue;
                    const glm::dvec3 d = (dr ? below : here)[std::size_t(c + dc)] - p;
                    row_edge2[std::size_t(r)] = std::max(row_edge2[std::size_t(r)], glm::dot(d, d));
                }
            }
            std::swap(here, below);
        }
    });
    double top = -std::numeric_limits<double>::infinity(), edge2 = 0.0;
    for (std::size_t r = 0; r < row_top.size(); ++r) top = std::max(top, row_top[r]), edge2 = std::max(edge2, row_edge2[r]);
    const double edge = std::sqrt(edge2);
    if (!(top > -std::numeric_limits<double>::infinity())) return -std::numeric_limits<float>::infinity();
    const double bound = top + edge + 1e-3 * (std::abs(top) + edge);
    const float f = float(bound);
    return double(f) < bound ? float_up(f) : f;
}

PlanBoxes::PlanBoxes(const DrainageGrid& g) : g_(&g) {
    coarse_ = g.factor > 1 && g.coarse_cols >= 2 && g.coarse_rows >= 2;
    affine_ = g.has_affine;
    factor_ = coarse_ ? double(g.factor) : 1.0;
    cols_ = coarse_ ? g.coarse_cols : g.cols, rows_ = coarse_ ? g.coarse_rows : g.rows;
    if (affine_) return;
    bcols_ = (cols_ + block - 1) / block, brows_ = (rows_ + block - 1) / block;
    lo_.assign(std::size_t(bcols_) * std::size_t(brows_), glm::dvec2(std::numeric_limits<double>::infinity()));
    hi_.assign(lo_.size(), glm::dvec2(-std::numeric_limits<double>::infinity()));
    parallel_chunks(std::size_t(brows_), 1, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t br = b0; br < b1; ++br)
            for (int r = int(br) * block; r < std::min(rows_, int(br + 1) * block); ++r)
                for (int c = 0; c < cols_; ++c) {
                    const glm::dvec2 p = node(c, r);
                    const std::size_t k = br * std::size_t(bcols_) + std::size_t(c / block);
                    lo_[k] = glm::min(lo_[k], p), hi_[k] = glm::max(hi_[k], p);
                }
    });
    if (bcols_ < window || brows_ < window) return;
    // the windows: each block's box rounded outward, then the least and most over each window's
    // rows of blocks, then over its columns
    const auto wc = std::size_t(bcols_ - window + 1), wr = std::size_t(brows_ - window + 1);
    window_lo_.resize(wc * wr), window_hi_.resize(wc * wr);
    parallel_chunks(wr, 16, [&](std::size_t r0, std::size_t r1) {
        std::vector<glm::vec2> across_lo(static_cast<std::size_t>(bcols_)), across_hi(static_cast<std::size_t>(bcols_));
        for (std::size_t wy = r0; wy < r1; ++wy) {
            for (std::size_t bc = 0; bc < std::size_t(bcols_); ++bc) {
                glm::vec2 l(std::numeric_limits<float>::infinity()), h = -l;
                for (std::size_t br = wy; br < wy + window; ++br) {
                    const std::size_t k = br * std::size_t(bcols_) + bc;
                    l = glm::min(l, glm::vec2(float_down(float(lo_[k].x)), float_down(float(lo_[k].y))));
                    h = glm::max(h, glm::vec2(float_up(float(hi_[k].x)), float_up(float(hi_[k].y))));
                }
                across_lo[bc] = l, across_hi[bc] = h;
            }
            for (std::size_t wx = 0; wx < wc; ++wx) {
                glm::vec2 l = across_lo[wx], h = across_hi[wx];
                for (std::size_t bc = wx + 1; bc < wx + window; ++bc) l = glm::min(l, across_lo[bc]), h = glm::max(h, across_hi[bc]);
                window_lo_[wy * wc + wx] = l, window_hi_[wy * wc + wx] = h;
            }
        }
    });
}

// The x, y grid_xy_at interpolates between at node (c, r): coarse_xy at factor > 1, grid_xy's
// at factor 1.
glm::dvec2 PlanBoxes::node(int c, int r) const {
    return coarse_ ? glm::dvec2(g_->coarse_xy[std::size_t(r) * std::size_t(cols_) + std::size_t(c)]) : grid_xy(*g_, c, r);
}

void PlanBoxes::plan_box(const CellBox& b, glm::vec2& lo, glm::vec2& hi) const {
    lo = glm::vec2(std::numeric_limits<float>::infinity()), hi = -lo;
    if (b.c1 < b.c0 || b.r1 < b.r0 || cols_ < 1 || rows_ < 1) return;
    // the nodes of every grid cell an index point of b may be interpolated from (grid_xy_at
    // clamps the cell to the grid's last but one node), one more each side
    auto first = [&](double x, int n) { return std::clamp(int(std::floor(x / factor_)) - 1, 0, n - 1); };
    auto last = [&](double x, int n) { return std::clamp(int(std::floor(x / factor_)) + 2, 0, n - 1); };
    const int c0 = first(b.c0, cols_), c1 = last(b.c1, cols_), r0 = first(b.r0, rows_), r1 = last(b.r1, rows_);
    glm::dvec2 l(std::numeric_limits<double>::infinity()), h = -l;
    if (affine_) {  // an affine image of the node range: its corners span it
        for (const glm::dvec2 p : {node(c0, r0), node(c1, r0), node(c0, r1), node(c1, r1)}) l = glm::min(l, p), h = glm::max(h, p);
    } else {
        const int bc0 = c0 / block, bc1 = c1 / block, br0 = r0 / block, br1 = r1 / block;
        if (!window_lo_.empty() && bc1 - bc0 + 1 >= window && br1 - br0 + 1 >= window) {
            // windows at every window-th block from the first and one ending at the last, each way
            const auto wc = std::size_t(bcols_ - window + 1);
            lo = glm::vec2(std::numeric_limits<float>::infinity()), hi = -lo;
            for (int wy = br0;; wy = std::min(wy + window, br1 - window + 1)) {
                for (int wx = bc0;; wx = std::min(wx + window, bc1 - window + 1)) {
                    const std::size_t k = std::size_t(wy) * wc + std::size_t(wx);
                    lo = glm::min(lo, window_lo_[k]), hi = glm::max(hi, window_hi_[k]);
                    if (wx == bc1 - window + 1) break;
                }
                if (wy == br1 - window + 1) break;
            }
            return;
        }
        for (int br = br0; br <= br1; ++br)
            for (int bc = bc0; bc <= bc1; ++bc) {
                const std::size_t k = std::size_t(br) * std::size_t(bcols_) + std::size_t(bc);
                l = glm::min(l, lo_[k]), h = glm::max(h, hi_[k]);
            }
    }
    // outward to floats: the vertices are the doubles rounded to floats
    lo = glm::vec2(float_down(float(l.x)), float_down(float(l.y)));
    hi = glm::vec2(float_up(float(h.x)), float_up(float(h.y)));
}

std::vector<std::uint8_t> encode_stem_bounds(const StemBound* b, std::size_t n) {
    std::vector<std::uint8_t> planes(2 * bound_fields * n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint16_t f[bound_fields] = {std::uint16_t(b[i].x0 - (i ? b[i - 1].x0 : 0)),
                                               std::uint16_t(b[i].y0 - (i ? b[i - 1].y0 : 0)),
                                               std::uint16_t(b[i].x1 - b[i].x0), std::uint16_t(b[i].y1 - b[i].y0),
                                               b[i].plan, b[i].rise};
        for (int k = 0; k < bound_fields; ++k) planes[2 * k * n + i] = std::uint8_t(f[k]), planes[(2 * k + 1) * n + i] = std::uint8_t(f[k] >> 8);
    }
    return encode_bytes(planes.data(), planes.size());
}
bool decode_stem_bounds(const std::uint8_t* coded, std::size_t size, StemBound* b, std::size_t n) {
    std::vector<std::uint8_t> planes(2 * bound_fields * n);
    if (!decode_bytes(coded, size, planes.data(), planes.size())) return false;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint16_t f[bound_fields];
        for (int k = 0; k < bound_fields; ++k) f[k] = std::uint16_t(planes[2 * k * n + i] | planes[(2 * k + 1) * n + i] << 8);
        b[i].x0 = std::uint16_t(f[0] + (i ? b[i - 1].x0 : 0)), b[i].y0 = std::uint16_t(f[1] + (i ? b[i - 1].y0 : 0));
        b[i].x1 = std::uint16_t(b[i].x0 + f[2]), b[i].y1 = std::uint16_t(b[i].y0 + f[3]), b[i].plan = f[4],
        b[i].rise = f[5];
    }
    return true;
}


std::vector<std::uint8_t> encode_stem_ids(const std::uint32_t* ids, std::size_t n) {
    std::vector<std::uint32_t> steps(n);
    for (std::size_t i = 0; i < n; ++i) steps[i] = ids[i] - (i ? ids[i - 1] : 0u);
    return encode_bytes(reinterpret_cast<const std::uint8_t*>(steps.data()), 4 * n);
}

bool decode_stem_ids(const std::uint8_t* coded, std::size_t size, std::uint32_t* ids, std::size_t n) {
    if (!decode_bytes(coded, size, reinterpret_cast<std::uint8_t*>(ids), 4 * n)) return false;
    for (std::size_t i = 1; i < n; ++i) {  // every step at least 1, no wrap
        if (ids[i] == 0 || ids[i - 1] > ~ids[i]) return false;
        ids[i] += ids[i - 1];
    }
    return true;
}

}  // namespace penink
