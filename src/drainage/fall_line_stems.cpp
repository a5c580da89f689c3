#include "drainage/fall_line_stems.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/parallel_chunks.hpp"
#include "drainage/polyline_smoothing.hpp"

namespace penink {

namespace {

constexpr double min_cos = 0.3420201433256687;    // cos 70 degrees

struct Frame {
    glm::dvec2 u{1.0, 0.0}, v{0.0, -1.0};  // plan steps of one column, one row
};

class GridField {
public:
    explicit GridField(const DrainageGrid& g) : g_(g) {}

    // Plan steps of a column and a row at the cell holding p (index space).
    Frame frame(glm::dvec2 p) const {
        int c, r;
        cell(p, c, r);
        const glm::dvec2 o = grid_xy(g_, c, r);
        return {grid_xy(g_, c + 1, r) - o, grid_xy(g_, c, r + 1) - o};
    }

    // dz/dc, dz/dr at p, bilinear between the four nodes' central differences; false beside nodata.
    bool gradient(glm::dvec2 p, glm::dvec2& grad) const {
        int c, r;
        cell(p, c, r);
        const double fu = std::clamp(p.x - c, 0.0, 1.0), fv = std::clamp(p.y - r, 0.0, 1.0);
        grad = glm::dvec2(0.0);
        const double w[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
        if (c >= 1 && r >= 1 && c + 2 < g_.cols && r + 2 < g_.rows && block_valid(c, r)) {
            // the 4 x 4 nodes around all hold data: central differences throughout
            const float* z = g_.z.data() + g_.index(c, r);
            const std::ptrdiff_t row = g_.cols;
            for (int k = 0; k < 4; ++k) {
                const float* n = z + (k >> 1) * row + (k & 1);
                grad += w[k] * glm::dvec2(0.5 * (double(n[1]) - n[-1]), 0.5 * (double(n[row]) - n[-row]));
            }
            return true;
        }
        for (int k = 0; k < 4; ++k) {
            glm::dvec2 n;
            if (!node_gradient(c + (k & 1), r + (k >> 1), n)) return false;
            grad += w[k] * n;
        }
        return true;
    }

    // Plan x, y of index point p.
    glm::dvec2 xy(glm::dvec2 p) const { return grid_xy_at(g_, p.x, p.y); }

private:
    const DrainageGrid& g_;

    void cell(glm::dvec2 p, int& c, int& r) const {
        c = int(std::clamp(std::floor(p.x), 0.0, double(g_.cols - 2)));
        r = int(std::clamp(std::floor(p.y), 0.0, double(g_.rows - 2)));
    }
    // The 4 x 4 nodes from (c - 1, r - 1) hold data (corners not needed, read anyway).
    bool block_valid(int c, int r) const {
        const std::uint8_t* v = g_.valid.data() + g_.index(c - 1, r - 1);
        unsigned all = 1;
        for (int j = 0; j < 4; ++j, v += g_.cols) all &= v[0] & v[1] & v[2] & v[3];
        return all != 0;
    }
    bool ok(int c, int r) const { return c >= 0 && r >= 0 && c < g_.cols && r < g_.rows && g_.valid[g_.index(c, r)]; }
    bool node_gradient(int c, int r, glm::dvec2& n) const {
        if (!ok(c, r)) return false;
        auto diff = [&](int dc, int dr, double& d) {
            const bool f = ok(c + dc, r + dr), b = ok(c - dc, r - dr);
            if (!f && !b) return false;
            const double zf = g_.z[g_.index(f ? c + dc : c, f ? r + dr : r)];
            const double zb = g_.z[g_.index(b ? c - dc : c, b ? r - dr : r)];
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
    const double a = glm::dot(f.u, f.u), b = glm::dot(f.u, f.v), c = glm::dot(f.v, f.v);
    const double det = a * c - b * b;
    if (!(std::abs(det) > 0.0)) return false;
    d = -glm::dvec2(c * gr.x - b * gr.y, a * gr.y - b * gr.x) / det;
    return d.x != 0.0 || d.y != 0.0;
}

void trace_stem(DrapedVertex* v, const std::uint32_t* cells, std::uint32_t n, const GridField& field, int cols,
                double sigma, double corridor, std::vector<glm::dvec2>& q, std::vector<glm::dvec2>& s) {
    q.resize(n);
    for (std::uint32_t k = 0; k < n; ++k) q[k] = {double(cells[k] % std::uint32_t(cols)), double(cells[k] / std::uint32_t(cols))};
    gaussian_smooth(q, sigma, s);
    glm::dvec2 p = s[0];
    // the grid's metric at the source serves the whole stem (a UTM-projected grid's cells change
    // shape by far less than a percent along one)
    const Frame f = field.frame(p);
    for (std::uint32_t k = 0; k + 1 < n; ++k) {
        const glm::dvec2 step = s[k + 1] - s[k];
        const double ds = norm(step.x, step.y);
        glm::dvec2 next = s[k + 1] + 0.8 * (p - s[k]);  // no usable fall line: along S, back towards it
        glm::dvec2 gr, d;
        if (ds > 0.0 && field.gradient(p, gr)) {
            if (descent(f, gr, d)) {
                const glm::dvec2 pt = step.x * f.u + step.y * f.v, pd = d.x * f.u + d.y * f.v;
                const double cosine = glm::dot(pt, pd) / (norm(pt.x, pt.y) * norm(pd.x, pd.y));
                if (cosine > min_cos) next = p + ds * d / norm(d.x, d.y);
            }
        }
        const glm::dvec2 e = next - s[k + 1];
        const double el = norm(e.x, e.y);
        p = el > corridor ? s[k + 1] + e * (corridor / el) : next;
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
    return o;
}

void trace_fall_lines(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                      const FallLineOptions& o) {
    if (g.cols < 2 || g.rows < 2) return;
    const GridField field(g);
    parallel_chunks(set.lines.size(), 1024, [&](std::size_t l0, std::size_t l1) {
        std::vector<glm::dvec2> q, s;
        for (std::size_t i = l0; i < l1; ++i) {
            const DrapedLine& l = set.lines[i];
            if (l.count < 3) continue;
            trace_stem(set.vertices.data() + l.first, cells.data() + l.first, l.count, field, g.cols, o.sigma,
                       o.corridor, q, s);
        }
    });
}

}  // namespace penink
