#include "drainage/fall_line_stems.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/floor_index.hpp"
#include "drainage/line_chunks.hpp"
#include "drainage/polyline_smoothing.hpp"

namespace penink {

namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;
constexpr double min_cos = 0.3420201433256687;    // cos 70 degrees

struct Frame {
    Frame(glm::dvec2 col, glm::dvec2 row)
        : u(col), v(row), a(glm::dot(u, u)), b(glm::dot(u, v)), c(glm::dot(v, v)), det(a * c - b * b) {}
    glm::dvec2 u, v;       // plan steps of one column, one row
    double a, b, c, det;   // the metric JᵀJ = [a b; b c] and its determinant
};

class GridField {
public:
    // The gradient comes from the DEM's own nodes (g.coarse_z at factor > 1, g.z at factor 1).
    explicit GridField(const DrainageGrid& g) : g_(g) {
        const std::size_t coarse = std::size_t(g.coarse_cols) * std::size_t(g.coarse_rows);
        if (g.factor > 1 && coarse > 0 && g.coarse_z.size() == coarse && g.coarse_valid.size() == coarse) {
            z_ = g.coarse_z.data(), valid_ = g.coarse_valid.data();
            cols_ = g.coarse_cols, rows_ = g.coarse_rows, scale_ = double(g.factor);
        } else {
            z_ = node_heights(g), valid_ = g.valid.data(), cols_ = g.cols, rows_ = g.rows, scale_ = 1.0;
            blocks_ = g.node_blocks.get();
        }
    }

    // Plan steps of a column and a row at the cell holding p (index space).
    Frame frame(glm::dvec2 p) const {
        const int c = floor_index(p.x, g_.cols - 2);
        const int r = floor_index(p.y, g_.rows - 2);
        const glm::dvec2 o = grid_xy(g_, c, r);
        return {grid_xy(g_, c + 1, r) - o, grid_xy(g_, c, r + 1) - o};
    }

    // The central differences at the four nodes of the last cell whose 4 x 4 nodes all hold data
    // (a thread's: a trace's next points mostly lie in the cell of the one before).
    struct CellDiffs {
        int c = -1, r = -1;
        glm::dvec2 node[4];
    };

    // dz/dc, dz/dr at fine index point p: bilinear between the four DEM nodes' central
    // differences around it; false beside nodata.
    bool gradient(glm::dvec2 fine, glm::dvec2& grad, CellDiffs& last) const {
        const glm::dvec2 p = scale_ == 1.0 ? fine : fine / scale_;  // x / 1 is x: no division at factor 1
        int c, r;
        cell(p, c, r);
        const double fu = std::clamp(p.x - c, 0.0, 1.0), fv = std::clamp(p.y - r, 0.0, 1.0);
        grad = glm::dvec2(0.0);
        const double w[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
        if (c != last.c || r != last.r) {
            if (c >= 1 && r >= 1 && c + 2 < cols_ && r + 2 < rows_ && block_valid(c, r)) {
                // the 4 x 4 nodes around all hold data: central differences throughout (their
                // corners' blocks hold every one of them)
                if (blocks_)
                    for (std::size_t i : {index(c - 1, r - 1), index(c + 2, r - 1), index(c - 1, r + 2), index(c + 2, r + 2)})
                        blocks_->need(i);
                const float* z = z_ + index(c, r);
                const std::ptrdiff_t row = cols_;
                for (int k = 0; k < 4; ++k) {
                    const float* n = z + (k >> 1) * row + (k & 1);
                    last.node[k] = glm::dvec2(0.5 * (double(n[1]) - n[-1]), 0.5 * (double(n[row]) - n[-row]));
                }
                last.c = c, last.r = r;
            } else {
                last.c = last.r = -1;
            }
        }
        if (last.c >= 0) {
            for (int k = 0; k < 4; ++k) grad += w[k] * last.node[k];
            if (scale_ != 1.0) grad /= scale_;
            return true;
        }
        for (int k = 0; k < 4; ++k) {
            glm::dvec2 n;
            if (!node_gradient(c + (k & 1), r + (k >> 1), n)) return false;
            grad += w[k] * n;
        }
        if (scale_ != 1.0) grad /= scale_;
        return true;
    }

    // Plan x, y of index point p.
    glm::dvec2 xy(glm::dvec2 p) const { return grid_xy_at(g_, p.x, p.y); }
    int cols() const { return g_.cols; }
    int rows() const { return g_.rows; }

private:
    const DrainageGrid& g_;
    const float* z_ = nullptr;  // the nodes the gradient comes from
    CellBlocks* blocks_ = nullptr;  // where z_ holds only the blocks filled (DrainageGrid::node_blocks)
    const std::uint8_t* valid_ = nullptr;
    int cols_ = 0, rows_ = 0;
    double scale_ = 1.0;  // fine cells a cell of theirs

    std::size_t index(int c, int r) const { return std::size_t(r) * std::size_t(cols_) + std::size_t(c); }
    void cell(glm::dvec2 p, int& c, int& r) const {
        c = floor_index(p.x, cols_ - 2);
        r = floor_index(p.y, rows_ - 2);
    }
    // The 4 x 4 nodes from (c - 1, r - 1) hold data (corners not needed, read anyway).
    bool block_valid(int c, int r) const {
        const std::uint8_t* v = valid_ + index(c - 1, r - 1);
        unsigned all = 1;
        for (int j = 0; j < 4; ++j, v += cols_) all &= v[0] & v[1] & v[2] & v[3];
        return all != 0;
    }
    bool ok(int c, int r) const { return c >= 0 && r >= 0 && c < cols_ && r < rows_ && valid_[index(c, r)]; }
    bool node_gradient(int c, int r, glm::dvec2& n) const {
        if (!ok(c, r)) return false;
        auto diff = [&](int dc, int dr, double& d) {
            const bool f = ok(c + dc, r + dr), b = ok(c - dc, r - dr);
            if (!f && !b) return false;
            const std::size_t nf = index(f ? c + dc : c, f ? r + dr : r), nb = index(b ? c - dc : c, b ? r - dr : r);
            if (blocks_) blocks_->need(nf), blocks_->need(nb);
            const double zf = z_[nf], zb = z_[nb];
            d = (zf - zb) / ((f ? 1 : 0) + (b ? 1 : 0));
            return true;
        };
        return diff(1, 0, n.x) && diff(0, 1, n.y);
    }
};

// Length of (x, y) (std::hypot's care for overflow is not needed for grid offsets and is slow).
inline double norm(double x, double y) { return std::sqrt(x * x + y * y); }

// Index-space direction of steepest descent for index-space gradient gr on frame f: -(JᵀJ)⁻¹ gr.
bool descent(const Frame& f, glm::dvec2 gr, glm::dvec2& d) {
    const double a = f.a, b = f.b, c = f.c, det = f.det;
    if (!(std::abs(det) > 0.0)) return false;
    d = -glm::dvec2(c * gr.x - b * gr.y, a * gr.y - b * gr.x) / det;
    return d.x != 0.0 || d.y != 0.0;
}

// Unit index-space fall direction at p on frame f; false where there is none (nodata, flat).
// `slope2`: the squared plan slope there (|grad z|^2 = -gr . d before d is made a unit vector).
bool fall_direction(const GridField& field, const Frame& f, glm::dvec2 p, glm::dvec2& d, GridField::CellDiffs& last,
                    double* slope2 = nullptr) {
    glm::dvec2 gr;
    if (!field.gradient(p, gr, last) || !descent(f, gr, d)) return false;
    if (slope2) *slope2 = -glm::dot(gr, d);
    d /= norm(d.x, d.y);
    return true;
}

// A fifth of the way back along `offset` (from the trace to S), at most half a step `ds`: a trace
// far off S comes back gradually instead of jumping.
glm::dvec2 back_towards(glm::dvec2 offset, double ds) {
    const glm::dvec2 b = 0.2 * offset;
    const double len = norm(b.x, b.y), cap = 0.5 * ds;
    return len > cap ? b * (cap / len) : b;
}

// One stem to trace: its n vertices (x, y moved in place) and the grid cells they came from.
struct Stem {
    DrapedVertex* v;
    const std::uint32_t* cells;
    std::uint32_t n;
};

// What a thread reuses from stem to stem: the cells as index-space points, and smoothed; the
// smoothing's kernel and the widening's thresholds (of the options, the same for every stem).
struct StemScratch {
    explicit StemScratch(const FallLineOptions& o)
        : kernel(o.sigma), widen_cos(std::cos(o.widen_max_deg * deg)),
          widen_slope2(std::pow(std::tan(o.widen_min_slope_deg * deg), 2)) {}
    std::vector<glm::dvec2> q, s;
    GridField::CellDiffs last;
    GaussianKernel kernel;
    double widen_cos, widen_slope2;
};

void trace_stem(const Stem& stem, const GridField& field, const FallLineOptions& o, StemScratch& scratch) {
    DrapedVertex* const v = stem.v;
    const std::uint32_t n = stem.n;
    std::vector<glm::dvec2>& q = scratch.q;
    std::vector<glm::dvec2>& s = scratch.s;
    const auto cols = std::uint32_t(field.cols());
    q.resize(n);
    for (std::uint32_t k = 0; k < n; ++k) q[k] = {double(stem.cells[k] % cols), double(stem.cells[k] / cols)};
    scratch.kernel.smooth(q, s);
    glm::dvec2 p = s[0];
    // the grid's metric at the source serves the whole stem (a UTM-projected grid's cells change
    // shape by far less than a percent along one)
    const Frame f = field.frame(p);
    const double widen_cos = scratch.widen_cos, widen_slope2 = scratch.widen_slope2;
    double run = o.corridor;  // the corridor, widening on slopes and narrowing on flats
    bool stopped = false;  // the trace left the grid: the remaining vertices stay where it left
    for (std::uint32_t k = 0; k + 1 < n; ++k) {
        if (stopped) {
            if (k + 2 < n) v[k + 1].x = v[k].x, v[k + 1].y = v[k].y;
            continue;
        }
        const glm::dvec2 step = s[k + 1] - s[k];
        const double ds = norm(step.x, step.y);
        bool falls = false;  // next = p + ds * d along the fall line, else along S, back towards it
        glm::dvec2 d1, d2, d;
        double slope2 = 0.0;
        bool along = false;  // the fall line runs with the stem: the corridor may widen
        if (ds > 0.0 && fall_direction(field, f, p, d1, scratch.last, &slope2)) {
            // Heun's step: the mean of the directions here and one step on (across a V-shaped
            // valley's floor they cancel across it and add along it)
            d = d1;
            if (fall_direction(field, f, p + ds * d1, d2, scratch.last)) {
                const glm::dvec2 m = d1 + d2;
                const double ml = norm(m.x, m.y);
                if (ml > 1e-6) d = m / ml;
            }
            const glm::dvec2 pt = step.x * f.u + step.y * f.v, pd = d.x * f.u + d.y * f.v;
            const double cosine = glm::dot(pt, pd) / (norm(pt.x, pt.y) * norm(pd.x, pd.y));
            along = cosine > widen_cos;
            falls = cosine > min_cos;
            const glm::dvec2 ahead = p + ds * d1;  // the fall line leaves the grid: the crease ends
            if (ahead.x < 0.0 || ahead.y < 0.0 || ahead.x > double(field.cols() - 1) || ahead.y > double(field.rows() - 1)) {
                stopped = true;
                if (k + 2 < n) v[k + 1].x = v[k].x, v[k + 1].y = v[k].y;
                continue;
            }
        }
        const glm::dvec2 next = falls ? p + ds * d : p + step + back_towards(s[k] - p, ds);
        run = slope2 > widen_slope2 && along ? std::min(o.max_corridor, run + o.widen * ds) : std::max(o.corridor, run - o.widen * ds);
        const glm::dvec2 e = next - s[k + 1];
        const double el = norm(e.x, e.y), corridor = std::min(o.max_corridor, run);
        const glm::dvec2 moved = el > corridor ? s[k + 1] + e * (corridor / el) : next;
        // a trace leaving the grid stops where it is instead of running along the grid's edge
        const bool inside = moved.x >= 0.0 && moved.y >= 0.0 && moved.x <= double(field.cols() - 1) && moved.y <= double(field.rows() - 1);
        if (!inside) {
            stopped = true;
            if (k + 2 < n) v[k + 1].x = v[k].x, v[k + 1].y = v[k].y;  // vertex k's plan position (the source's at k = 0)
            continue;
        }
        p = moved;
        if (k + 2 < n) {
            const glm::dvec2 xy = field.xy(p);
            v[k + 1].x = float(xy.x), v[k + 1].y = float(xy.y);
        }
    }
    const glm::dvec2 xy = field.xy(p);  // the last vertex: its junction's (joined later) or where the trace ends
    v[n - 1].x = float(xy.x), v[n - 1].y = float(xy.y);
}

}  // namespace

FallLineOptions fall_line_options(const DrainageGrid& g) {
    FallLineOptions o;
    o.sigma = std::max(2.0, double(g.factor));
    o.corridor = std::max(3.0, double(g.factor));
    o.meet = o.corridor;
    o.max_corridor = std::max(o.corridor, o.max_corridor_dem_cells * double(g.factor));
    return o;
}

void trace_fall_lines(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                      const FallLineOptions& o) {
    if (g.cols < 2 || g.rows < 2) return;
    const GridField field(g);
    parallel_line_chunks(set.lines, set.vertices.size(), 0, set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1) {
        StemScratch scratch(o);
        for (std::size_t i = l0; i < l1; ++i) {
            const DrapedLine& l = set.lines[i];
            if (l.count < 3) continue;
            trace_stem(Stem{set.vertices.data() + l.first, cells.data() + l.first, l.count}, field, o, scratch);
        }
    });
}

}  // namespace penink
