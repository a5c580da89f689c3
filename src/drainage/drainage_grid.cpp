#include "drainage/drainage_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <GeographicLib/Constants.hpp>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "core/floor_index.hpp"
#include "core/parallel_chunks.hpp"
#include "surface/pn_triangle.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

namespace {

// Triangle of coarse cell (C, R) holding local point (u, v) in [0,1]^2 (u east, v south) and its
// barycentric weights: (a, d, b) when u >= v, else (a, s, d), as in mesh_from_terrain.
struct CellTriangle {
    std::array<std::size_t, 3> node;
    glm::vec3 w;
    int which;  // 0 = (a,s,d), 1 = (a,d,b)
};

CellTriangle cell_triangle(int ccols, int C, int R, double u, double v) {
    const std::size_t a = std::size_t(R) * ccols + C, b = a + 1;
    const std::size_t s = a + ccols, d = s + 1;
    if (u >= v) return {{a, d, b}, glm::vec3(float(1.0 - u), float(v), float(u - v)), 1};
    return {{a, s, d}, glm::vec3(float(1.0 - v), float(v - u), float(u)), 0};
}

// Cell and local coordinate of fine index k along an axis of n coarse nodes.
void locate(int k, int f, int n, int& cell, double& t) {
    cell = std::min(k / f, n - 2);
    t = double(k - cell * f) / f;
}

// Replaces vertices of the triangle without data by its first valid vertex (they carry zero
// weight for every node the triangle serves), so evaluations stay finite.
std::array<std::size_t, 3> substitute(std::array<std::size_t, 3> n,
                                      const std::vector<std::uint8_t>& valid) {
    std::size_t keep = n[0];
    for (std::size_t i : n)
        if (valid[i]) { keep = i; break; }
    for (std::size_t& i : n)
        if (!valid[i]) i = keep;
    return n;
}

bool node_valid(const CellTriangle& t, const std::vector<std::uint8_t>& valid) {
    for (int k = 0; k < 3; ++k)
        if (t.w[k] > 0.0f && !valid[t.node[k]]) return false;
    return true;
}

PnPatch cell_patch(const SurfaceMesh& m, const std::vector<std::uint8_t>& valid,
                   const CellTriangle& t) {
    const auto n = substitute(t.node, valid);
    return pn_patch(m.pos[n[0]], m.pos[n[1]], m.pos[n[2]], m.normal[n[0]], m.normal[n[1]],
                    m.normal[n[2]]);
}

// x, y of the nodes, a row at a time (t.cols of them): the Terrain's pos, or after a heights-only
// read (pos empty) its xy (a geographic DEM) or affine_node_xy on its grid. Without rotation
// terms (gt[2] = gt[4] = 0) the other coordinate's term adds zero, so x depends on the column
// only and y on the row only: the columns' x are computed once, the same floats.
struct RowXY {
    const Terrain& t;
    AffineNodes a;
    std::vector<float> xs;  // per column, on an axis-aligned heights-only grid

    explicit RowXY(const Terrain& terrain) : t(terrain) {
        terrain_affine(t, a);
        if (!t.pos.empty() || !t.xy.empty() || a.gt[2] != 0.0 || a.gt[4] != 0.0) return;
        xs.resize(std::size_t(t.cols));
        for (int c = 0; c < t.cols; ++c) xs[std::size_t(c)] = affine_node_xy(a, t.origin, c, 0).x;
    }
    float y(int r) const { return affine_node_xy(a, t.origin, 0, r).y; }  // a row's, with xs
    void row(int r, std::vector<glm::vec2>& out) const {
        out.resize(std::size_t(t.cols));
        const float y = xs.empty() ? 0.0f : this->y(r);
        for (int c = 0; c < t.cols; ++c)
            out[std::size_t(c)] = !t.pos.empty() ? glm::vec2(t.pos[t.index(c, r)])
                                  : !t.xy.empty() ? t.xy[t.index(c, r)]
                                  : xs.empty()   ? affine_node_xy(a, t.origin, c, r)
                                                 : glm::vec2(xs[std::size_t(c)], y);
    }
};

// Sums of the x, y step lengths between valid neighbours along rows (sx, nx) and columns (sy, ny).
struct StepSums {
    double sx = 0, sy = 0;
    std::size_t nx = 0, ny = 0;
    // Row r's steps: along(c) from column c to c + 1, down(c) from row r to r + 1.
    template <class Along, class Down> void add_row(const Terrain& t, int r, Along&& along, Down&& down) {
        for (int c = 0; c < t.cols; ++c) {
            const std::size_t i = t.index(c, r);
            if (!t.valid[i]) continue;
            if (c + 1 < t.cols && t.valid[i + 1]) sx += along(c), ++nx;
            if (r + 1 < t.rows && t.valid[i + t.cols]) sy += down(c), ++ny;
        }
    }
};

// Mean length of the x, y steps between valid neighbours along rows (dx) and columns (dy), summed
// over fixed blocks of rows in parallel and the blocks' sums added in order: the same doubles
// whatever the number of threads.
void mean_spacing(const Terrain& t, double& dx, double& dy) {
    constexpr std::size_t block_rows = 64;
    const RowXY xy(t);
    std::vector<StepSums> block((std::size_t(t.rows) + block_rows - 1) / block_rows);
    // On an axis-aligned heights-only grid a step's length is the column's along rows and the
    // row's along columns (the other coordinate's difference is 0): the same floats, each made once.
    std::vector<float> along_row;
    if (!xy.xs.empty())
        for (int c = 0; c + 1 < t.cols; ++c)
            along_row.push_back(glm::length(glm::vec2(xy.xs[std::size_t(c) + 1] - xy.xs[std::size_t(c)], 0.0f)));
    parallel_chunks(block.size(), 1, [&](std::size_t b0, std::size_t b1) {
        std::vector<glm::vec2> row, below;
        for (std::size_t b = b0; b < b1; ++b) {
            const int r0 = int(b * block_rows), r1 = std::min(t.rows, int((b + 1) * block_rows));
            if (!along_row.empty()) {
                for (int r = r0; r < r1; ++r) {
                    const float ly = r + 1 < t.rows ? glm::length(glm::vec2(0.0f, xy.y(r + 1) - xy.y(r))) : 0.0f;
                    block[b].add_row(t, r, [&](int c) { return along_row[std::size_t(c)]; }, [&](int) { return ly; });
                }
                continue;
            }
            xy.row(r0, below);
            for (int r = r0; r < r1; ++r) {
                std::swap(row, below);
                if (r + 1 < t.rows) xy.row(r + 1, below);
                block[b].add_row(
                    t, r, [&](int c) { return glm::length(row[std::size_t(c) + 1] - row[std::size_t(c)]); },
                    [&](int c) { return glm::length(below[std::size_t(c)] - row[std::size_t(c)]); });
            }
        }
    });
    StepSums s;
    for (const StepSums& b : block) s.sx += b.sx, s.sy += b.sy, s.nx += b.nx, s.ny += b.ny;
    dx = s.nx ? s.sx / s.nx : 1.0, dy = s.ny ? s.sy / s.ny : 1.0;
    if (!(dx > 0)) dx = 1.0;
    if (!(dy > 0)) dy = 1.0;
}

// Fills the fine nodes of coarse cell (C, R): its interior and its north and west sides, plus
// the east / south sides on the last column / row.
void resample_cell(const Terrain& t, const SurfaceMesh& m, int C, int R, DrainageGrid& g) {
    const int f = g.factor;
    const CellTriangle t0 = cell_triangle(t.cols, C, R, 0.25, 0.75);
    const CellTriangle t1 = cell_triangle(t.cols, C, R, 0.75, 0.25);
    const PnPatch p0 = cell_patch(m, t.valid, t0), p1 = cell_patch(m, t.valid, t1);
    const int i1 = C == t.cols - 2 ? f : f - 1, j1 = R == t.rows - 2 ? f : f - 1;
    for (int j = 0; j <= j1; ++j)
        for (int i = 0; i <= i1; ++i) {
            const CellTriangle tri = cell_triangle(t.cols, C, R, double(i) / f, double(j) / f);
            const std::size_t k = g.index(C * f + i, R * f + j);
            if (!node_valid(tri, t.valid)) continue;
            g.valid[k] = 1;
            g.z[k] = pn_position(tri.which ? p1 : p0, tri.w).z;
        }
}

}  // namespace

std::size_t resampled_size(const Terrain& t, int factor) {
    return std::size_t(std::max(t.cols - 1, 0) * std::size_t(factor) + 1) *
           (std::size_t(std::max(t.rows - 1, 0)) * factor + 1);
}

namespace {

// A heights-only read (DemOptions: no positions) resamples at factor 1 only, and only with its
// nodes' x, y (UTM) or an affine grid.
void check_node_xy(const Terrain& t, int factor, bool affine) {
    if (t.pos.empty() && (factor > 1 || (!affine && t.xy.empty())))
        throw Error("drainage", t.source, "DEM read without positions resamples at factor 1 only", ExitCode::internal);
}

// The grid of t at `factor`, everything but z: size, origin, affine grid, masks, spacing, and the
// coarse x, y where grid_xy needs them (not at factor 1 on an affine grid).
DrainageGrid grid_frame(const Terrain& t, int factor) {
    if (factor < 1) throw Error("drainage", t.source, "resample factor must be >= 1");
    if (t.cols < 2 || t.rows < 2)
        throw Error("drainage", t.source, "DEM too small for drainage (needs at least 2x2 nodes)");
    DrainageGrid g;
    g.factor = factor;
    g.cols = (t.cols - 1) * factor + 1, g.rows = (t.rows - 1) * factor + 1;
    g.origin = t.origin;
    g.has_affine = terrain_affine(t, g.affine);
    check_node_xy(t, factor, g.has_affine);
    g.coarse_cols = t.cols, g.coarse_rows = t.rows, g.coarse_valid = t.valid;
    g.valid = factor == 1 ? t.valid : std::vector<std::uint8_t>(g.size(), 0);
    mean_spacing(t, g.dx, g.dy);
    g.dx /= factor, g.dy /= factor;
    if (!t.pos.empty() && (factor > 1 || !g.has_affine)) g.coarse_xy.assign(t.pos.begin(), t.pos.end());
    return g;
}

// z at factor 1 (the PN patch interpolates its corners: the nodes themselves), 0 at nodata.
void node_heights(const Terrain& t, DrainageGrid& g) {
    g.z.resize(g.size());
    parallel_chunks(g.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i) g.z[i] = !t.valid[i] ? 0.0f : t.pos.empty() ? t.z[i] : t.pos[i].z;
    });
}

}  // namespace

DrainageGrid resample_pn(const Terrain& t, int factor) {
    DrainageGrid g = grid_frame(t, factor);
    if (factor == 1) {
        node_heights(t, g);
        return g;
    }
    g.z.assign(g.size(), 0.0f);
    g.coarse_z.resize(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) g.coarse_z[i] = t.pos[i].z;
    const SurfaceMesh mesh = mesh_from_terrain(t);
    for (int R = 0; R + 1 < t.rows; ++R)
        for (int C = 0; C + 1 < t.cols; ++C) resample_cell(t, mesh, C, R, g);
    return g;
}

DrainageGrid resample_pn_releasing(Terrain& t, int factor) {
    DrainageGrid g;
    if (factor == 1 && !t.z.empty()) {  // heights-only: z taken over, 0 at nodata
        g = grid_frame(t, factor);
        take_node_arrays(t, g.z, g.coarse_xy);
        // the mask taken over too: the coarse one is the same at factor 1 (coarse_valid_shared)
        g.valid = std::move(t.valid), std::vector<std::uint8_t>().swap(g.coarse_valid);
        GeographicNodes geo;
        if (!g.coarse_xy.empty() && terrain_geographic(t, geo)) {
            try {
                g.node_xy = std::make_shared<const GeographicNodeXY>(geo, t.origin);
            } catch (const GeographicLib::GeographicErr&) {  // the read projected it: cannot happen
            }
        }
    } else {
        g = resample_pn(t, factor);
    }
    std::vector<glm::vec3>().swap(t.pos);
    std::vector<float>().swap(t.z);
    NodeXY().swap(t.xy);
    return g;
}

void take_node_heights(Terrain& t, std::vector<float>& z) {
    z = std::move(t.z);
    parallel_chunks(z.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i)
            if (!t.valid[i]) z[i] = 0.0f;
    });
}

void take_node_arrays(Terrain& t, std::vector<float>& z, NodeXY& xy) {
    AffineNodes affine;
    check_node_xy(t, 1, terrain_affine(t, affine));
    xy = std::move(t.xy);  // a geographic DEM's nodes in UTM
    take_node_heights(t, z);
}

bool release_node_xy(DrainageGrid& g) {
    // (not where it is made by blocks: their filling writes into it)
    if (!g.node_xy || g.node_blocks || g.factor != 1 || g.coarse_xy.size() != g.size()) return false;
    NodeXY().swap(g.coarse_xy);
    return true;
}

void restore_node_xy(DrainageGrid& g) {
    if (!g.node_xy || g.factor != 1 || g.coarse_xy.size() == g.size()) return;
    g.coarse_xy.resize(g.size());
    parallel_chunks(std::size_t(g.rows), 64, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t r = r0; r < r1; ++r) g.node_xy->span(int(r), 0, g.cols, g.coarse_xy.data() + r * std::size_t(g.cols));
    });
    g.xy_rows.reset();  // (what they were read from meanwhile, if anything)
}

void readable_node_xy(DrainageGrid& g) {
    if (!g.node_xy || g.factor != 1 || g.coarse_xy.size() == g.size() || g.xy_rows) return;
    if (!g.node_blocks && NodeXYRows::possible(*g.node_xy)) g.xy_rows = std::make_shared<const NodeXYRows>(g.node_xy, g.rows);
    else restore_node_xy(g);
}

DrainageGrid make_regular_grid(int cols, int rows, double spacing, std::vector<float> z,
                               std::vector<std::uint8_t> valid) {
    DrainageGrid g;
    g.cols = cols, g.rows = rows, g.factor = 1, g.dx = g.dy = spacing;
    g.z = std::move(z);
    g.valid = valid.empty() ? std::vector<std::uint8_t>(g.size(), 1) : std::move(valid);
    g.coarse_cols = cols, g.coarse_rows = rows, g.coarse_valid = g.valid;
    g.coarse_xy.resize(g.size());
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            g.coarse_xy[g.index(c, r)] = glm::vec2(float(c * spacing), float(-r * spacing));
    return g;
}

namespace {

// The coarse nodes' mask: the fine one where it is left empty at factor 1 (the same mask).
const std::vector<std::uint8_t>& coarse_mask(const DrainageGrid& g) {
    return g.factor == 1 && g.coarse_valid.empty() ? g.valid : g.coarse_valid;
}

}  // namespace

glm::dvec2 grid_xy(const DrainageGrid& g, int c, int r) {
    if (g.factor == 1) {  // the node itself (the interpolation puts weight 1 on it)
        if (g.has_affine) return glm::dvec2(affine_node_xy(g.affine, g.origin, c, r));
        if (g.coarse_xy.size() == g.size()) {
            need_node(g, g.index(c, r));
            return glm::dvec2(g.coarse_xy[g.index(c, r)]);
        }
        if (g.xy_rows) return glm::dvec2(g.xy_rows->at(c, r));  // released, its rows' samples held
        if (g.node_xy) {  // released (release_node_xy): the node's alone, made again
            glm::vec2 p;
            g.node_xy->span(r, c, c + 1, &p);
            return glm::dvec2(p);
        }
    }
    if (g.coarse_cols < 2 || g.coarse_rows < 2)
        return glm::dvec2(c * g.dx, -r * g.dy);
    int C, R;
    double u, v;
    locate(c, g.factor, g.coarse_cols, C, u);
    locate(r, g.factor, g.coarse_rows, R, v);
    const CellTriangle tri = cell_triangle(g.coarse_cols, C, R, u, v);
    const auto n = substitute(tri.node, coarse_mask(g));
    glm::dvec2 p(0.0);
    for (int k = 0; k < 3; ++k) p += double(tri.w[k]) * glm::dvec2(g.coarse_xy[n[k]]);
    return p;
}

glm::dvec2 grid_xy_at(const DrainageGrid& g, double c, double r) {
    if (g.factor == 1 || g.coarse_cols < 2 || g.coarse_rows < 2) {  // bilinear between the nodes
        const int c0 = floor_index(c, g.cols - 2);
        const int r0 = floor_index(r, g.rows - 2);
        const double u = std::clamp(c - c0, 0.0, 1.0), v = std::clamp(r - r0, 0.0, 1.0);
        if (g.factor == 1 && !g.has_affine && g.coarse_xy.size() == g.size()) {  // grid_xy's nodes, read here
            const std::size_t at = g.index(c0, r0), row = std::size_t(g.cols);
            if (g.node_blocks)
                for (std::size_t i : {at, at + 1, at + row, at + row + 1}) g.node_blocks->need(i);
            const glm::vec2* n = g.coarse_xy.data() + at;
            return (1 - v) * ((1 - u) * glm::dvec2(n[0]) + u * glm::dvec2(n[1])) +
                   v * ((1 - u) * glm::dvec2(n[row]) + u * glm::dvec2(n[row + 1]));
        }
        return (1 - v) * ((1 - u) * grid_xy(g, c0, r0) + u * grid_xy(g, c0 + 1, r0)) +
               v * ((1 - u) * grid_xy(g, c0, r0 + 1) + u * grid_xy(g, c0 + 1, r0 + 1));
    }
    const double f = g.factor;
    const int C = floor_index(c / f, g.coarse_cols - 2);
    const int R = floor_index(r / f, g.coarse_rows - 2);
    const double u = std::clamp(c / f - C, 0.0, 1.0), v = std::clamp(r / f - R, 0.0, 1.0);
    const CellTriangle tri = cell_triangle(g.coarse_cols, C, R, u, v);
    const auto n = substitute(tri.node, coarse_mask(g));
    glm::dvec2 p(0.0);
    for (int k = 0; k < 3; ++k) p += double(tri.w[k]) * glm::dvec2(g.coarse_xy[n[k]]);
    return p;
}

}  // namespace penink
