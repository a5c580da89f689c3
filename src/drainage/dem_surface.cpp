#include "drainage/dem_surface.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "surface/grid_cell.hpp"
#include "surface/pn_triangle.hpp"

namespace penink {

DemSurface::DemSurface(const DrainageGrid& g, Normals normals) {
    if (g.factor == 1) {
        cols_ = g.cols, rows_ = g.rows, valid_ = g.valid.data(), z_ = node_heights(g);
        if (!g.has_affine && g.coarse_xy.size() != g.size() && !g.xy_rows)
            throw Error("drainage", "", "drainage grid without node positions", ExitCode::internal);
        if (!g.has_affine && g.coarse_xy.size() == g.size()) xy_ = g.coarse_xy.data();
        else if (!g.has_affine) xy_rows_ = g.xy_rows.get();
        node_blocks_ = g.node_blocks.get();
    } else {
        cols_ = g.coarse_cols, rows_ = g.coarse_rows, valid_ = g.coarse_valid.data(), z_ = g.coarse_z.data();
        const std::size_t n = std::size_t(cols_) * std::size_t(rows_);
        if (g.coarse_xy.size() != n || g.coarse_z.size() != n || g.coarse_valid.size() != n)
            throw Error("drainage", "", "drainage grid without its DEM nodes", ExitCode::internal);
        xy_ = g.coarse_xy.data();
    }
    if (std::size_t(cols_) * std::size_t(rows_) >= 0xffffffffu)
        throw Error("drainage", "", "DEM too large to drape lines on (4 G nodes or more)", ExitCode::internal);
    if (g.has_affine) affine_ = true, nodes_ = g.affine;
    origin_ = g.origin;
    if (affine_) {
        const double a = nodes_.gt[1], b = nodes_.gt[2], c = nodes_.gt[4], d = nodes_.gt[5], det = a * d - b * c;
        if (det != 0.0 && std::isfinite(det)) inv_[0] = d / det, inv_[1] = -b / det, inv_[2] = -c / det, inv_[3] = a / det;
        if (!xy_ && nodes_.gt[2] == 0.0 && nodes_.gt[4] == 0.0) {  // x by column, y by row: the same floats
            col_x_.resize(std::size_t(cols_)), row_y_.resize(std::size_t(rows_));
            for (int k = 0; k < cols_; ++k) col_x_[std::size_t(k)] = affine_node_xy(nodes_, origin_, k, 0).x;
            for (int k = 0; k < rows_; ++k) row_y_[std::size_t(k)] = affine_node_xy(nodes_, origin_, 0, k).y;
        }
    }
    if (normals == Normals::all) make_normals();
}

DemSurface::DemSurface(const Terrain& t) {
    if (t.pos.size() != t.size() || t.valid.size() != t.size())
        throw Error("drainage", t.source, "DEM read without positions", ExitCode::internal);
    if (t.size() >= 0xffffffffu)
        throw Error("drainage", t.source, "DEM too large to drape lines on (4 G nodes or more)", ExitCode::internal);
    cols_ = t.cols, rows_ = t.rows, valid_ = t.valid.data(), pos_ = t.pos.data(), origin_ = t.origin;
    if (terrain_affine(t, nodes_)) {
        affine_ = true;
        const double a = nodes_.gt[1], b = nodes_.gt[2], c = nodes_.gt[4], d = nodes_.gt[5], det = a * d - b * c;
        if (det != 0.0 && std::isfinite(det)) inv_[0] = d / det, inv_[1] = -b / det, inv_[2] = -c / det, inv_[3] = a / det;
    }
    make_normals();
}

namespace {

// The unit normals of the two triangles of each cell of a row (compute_normals' face normals),
// and whether each triangle is part of the surface.
struct FaceRow {
    std::vector<glm::vec3> n;  // 2 per cell
    std::vector<std::uint8_t> present;
};

// compute_normals' face normal of triangle `which` of cell (c, r), a triangle of the surface
// (`node`: with_nodes' accessor).
template <class Node> glm::vec3 face_normal(const DemSurface& s, const Node& node, int c, int r, int which) {
    const std::size_t i = s.index(c, r), j = s.index(c, r + 1);
    const glm::vec3 a = node(c, r, i), d = node(c + 1, r + 1, j + 1);
    const glm::vec3 p1 = which == 0 ? node(c, r + 1, j) : d, p2 = which == 0 ? d : node(c + 1, r, i + 1);
    const glm::vec3 n = glm::cross(p1 - a, p2 - a);
    const float len = glm::length(n);
    return len > 0.0f ? n / len : glm::vec3(0, 0, 1);
}

// The vertex normal from the sum of its incident faces' normals.
glm::vec3 unit_sum(const glm::vec3& sum) {
    const float len = glm::length(sum);
    return len > 1e-12f ? sum / len : glm::vec3(0, 0, 1);
}

void face_row(const DemSurface& s, int r, FaceRow& out) {
    const std::size_t cells = std::size_t(s.cols() - 1);
    out.n.resize(2 * cells), out.present.assign(2 * cells, 0);
    if (r < 0 || r > s.rows() - 2) return;
    s.with_nodes([&](const auto& node) {
        for (int c = 0; c + 1 < s.cols(); ++c)
            for (int which = 0; which < 2; ++which) {
                if (!s.triangle_valid(c, r, which)) continue;
                out.n[2 * std::size_t(c) + which] = face_normal(s, node, c, r, which);
                out.present[2 * std::size_t(c) + which] = 1;
            }
    });
}

}  // namespace

// compute_normals: each node sums the unit normals of its incident triangles in mesh order
// (cells row-major, (NW, SW, SE) before (NW, SE, NE)): it is SE of cell (c-1, r-1) (both
// triangles), SW of (c, r-1) (the first), NE of (c-1, r) (the second), NW of (c, r) (both).
// Rows of nodes in parallel chunks, each with the face normals of the cell rows above and below.
void DemSurface::make_normals() {
    normals_.resize(std::size_t(cols_) * std::size_t(rows_));
    parallel_chunks(std::size_t(rows_), 64, [&](std::size_t r0, std::size_t r1) {
        FaceRow above, below;
        face_row(*this, int(r0) - 1, above);
        for (std::size_t r = r0; r < r1; ++r) {
            face_row(*this, int(r), below);
            for (int c = 0; c < cols_; ++c) {
                glm::vec3 sum(0.0f);
                auto add = [&](const FaceRow& f, int cell, int which) {
                    if (cell < 0 || cell > cols_ - 2) return;
                    const std::size_t k = 2 * std::size_t(cell) + std::size_t(which);
                    if (f.present[k]) sum += f.n[k];
                };
                add(above, c - 1, 0), add(above, c - 1, 1), add(above, c, 0);
                add(below, c - 1, 1), add(below, c, 0), add(below, c, 1);
                normals_[index(c, int(r))] = unit_sum(sum);
            }
            std::swap(above, below);
        }
    });
}

namespace {

// make_normals' sum for node (c, r) alone: the unit normals of its incident triangles of the
// surface, face(cc, rr, which) each, in the same order.
template <class Face> glm::vec3 node_face_sum(const DemSurface& s, int c, int r, Face&& face) {
    glm::vec3 sum(0.0f);
    auto add = [&](int cc, int rr, int which) {
        if (s.triangle_valid(cc, rr, which)) sum += face(cc, rr, which);
    };
    add(c - 1, r - 1, 0), add(c - 1, r - 1, 1), add(c, r - 1, 0);
    add(c - 1, r, 1), add(c, r, 0), add(c, r, 1);
    return unit_sum(sum);
}

}  // namespace

glm::vec3 DemSurface::node_normal(std::size_t i) const {
    const int c = int(i % std::size_t(cols_)), r = int(i / std::size_t(cols_));
    return with_nodes([&](const auto& node) {
        return node_face_sum(*this, c, r, [&](int cc, int rr, int which) { return face_normal(*this, node, cc, rr, which); });
    });
}

glm::vec3 DemSurface::node_normal(int c, int r, FaceNormals& faces, NodeXYCache* cache) const {
    constexpr std::size_t side = 64;
    if (faces.slots.empty()) faces.slots.assign(2 * side * side, {0, glm::vec3(0.0f)});
    return with_nodes([&](const auto& node) {
        return node_face_sum(*this, c, r, [&](int cc, int rr, int which) {
            auto& slot = faces.slots[(std::size_t(cc) % side + std::size_t(rr) % side * side) * 2 + std::size_t(which)];
            const std::uint64_t key = (std::uint64_t(index(cc, rr)) << 1 | std::uint64_t(which)) + 1;
            if (slot.first != key) slot = {key, face_normal(*this, node, cc, rr, which)};
            return slot.second;
        });
    }, cache);
}

DemDraper::DemDraper(const DemSurface& s) : s_(&s) {
    if (!s.normals_made()) made_.assign(64 * 64, {~0u, glm::vec3(0.0f)});
}

// On jacksboro refined 10 times (13.9 M nodes), the first whole view's crease tiles asked for
// 33 M normals of 14 M nodes: most nodes are made once whatever the slots, and the faces kept
// make each of their 6 faces a third as often (a face serves 3 nodes).
glm::vec3 DemDraper::normal(std::uint32_t i) const {
    if (made_.empty()) return s_->normal(std::size_t(i));
    const auto cols = std::uint32_t(s_->cols());
    const std::uint32_t c = i % cols, r = i / cols;
    auto& slot = made_[c % 64 + r % 64 * 64];
    if (slot.first != i) slot = {i, s_->node_normal(int(c), int(r), faces_, &xy_)};
    return slot.second;
}

// The cell the inverse of the affine node formula puts (x, y) in (clamped to the grid); false
// when the formula cannot be inverted or the point lies more than a cell off the grid.
bool DemSurface::affine_guess(double x, double y, int& c, int& r) const {
    if (!affine_ || (inv_[0] == 0.0 && inv_[1] == 0.0)) return false;
    const double wx = (x + origin_.x) / nodes_.unit - nodes_.gt[0], wy = (y + origin_.y) / nodes_.unit - nodes_.gt[3];
    const double fc = inv_[0] * wx + inv_[1] * wy - 0.5 - nodes_.col0;
    const double fr = inv_[2] * wx + inv_[3] * wy - 0.5 - nodes_.row0;
    if (!(fc > -2.0 && fr > -2.0 && fc < cols_ + 1.0 && fr < rows_ + 1.0)) return false;
    c = std::clamp(int(std::floor(fc)), 0, cols_ - 2);
    r = std::clamp(int(std::floor(fr)), 0, rows_ - 2);
    return true;
}


bool DemSurface::find_cell(double x, double y, int& c, int& r) const {
    if (cols_ < 2 || rows_ < 2 || !std::isfinite(x) || !std::isfinite(y)) return false;
    if (affine_) {
        if (!affine_guess(x, y, c, r)) return false;
        if (!pos_ && !xy_ && !xy_rows_) return true;  // the nodes are the formula's: its cell
    }
    return with_node_xy([&](const auto& xy) {  // the walk's node positions
        if (!affine_ && (c < 0 || r < 0 || c > cols_ - 2 || r > rows_ - 2) && !outline_cell(xy, cols_, rows_, x, y, c, r))
            return false;
        return walk_to_cell(xy, cols_, rows_, x, y, c, r);  // stored nodes: the formula's cell starts the walk
    });
}

namespace {

// triangle_hit's barycentric test of (x, y) in the triangle of plan corners p0, p1, p2 (u weights
// p1, w weights p2), the same doubles: false when the triangle is degenerate.
struct PlanBary {
    double u = 0.0, w = 0.0;
    bool ok = false;
    PlanBary(double x, double y, glm::dvec2 p0, glm::dvec2 p1, glm::dvec2 p2) {
        const double det = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
        if (std::abs(det) < 1e-12) return;
        u = ((x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (y - p0.y)) / det;
        w = ((p1.x - p0.x) * (y - p0.y) - (x - p0.x) * (p1.y - p0.y)) / det;
        ok = true;
    }
    // 1e-5 of the triangle's size from every edge
    bool inside() const { return ok && !(u < 1e-5 || w < 1e-5 || u + w > 1.0 - 1e-5); }
};

}  // namespace

// Triangle `which` of cell (c, r) tested as TerrainLocator::locate tests it: true when (x, y)
// lies in it within the tolerance `eps` of each barycentric coordinate (the hit filled in).
bool DemDraper::triangle_hit(double x, double y, int c, int r, int which, double eps, DemHit& hit) const {
    if (!s_->triangle_valid(c, r, which)) return false;
    const int nc[3] = {c, which == 0 ? c : c + 1, c + 1};
    const int nr[3] = {r, r + 1, which == 0 ? r + 1 : r};
    const PlanBary b(x, y, glm::dvec2(s_->node_xy(nc[0], nr[0])), glm::dvec2(s_->node_xy(nc[1], nr[1])),
                     glm::dvec2(s_->node_xy(nc[2], nr[2])));
    if (!b.ok) return false;
    const double u = b.u, w = b.w;
    if (u < -eps || w < -eps || u + w > 1.0 + eps) return false;
    for (int k = 0; k < 3; ++k) hit.node[k] = std::uint32_t(s_->index(nc[k], nr[k]));
    hit.bary = glm::vec3(float(1.0 - u - w), float(u), float(w));
    hit.cell = std::uint32_t(r) * std::uint32_t(s_->cols() - 1) + std::uint32_t(c);
    return true;
}

// The triangle of cell (c, r) that (x, y) lies well inside (1e-5 of its size from every edge;
// triangle_hit's test, the same doubles), the hit filled in; false when there is none. `xy`:
// the surface's node_xy (with_node_xy).
template <class XY>
bool DemDraper::inside_hit(const XY& xy, double x, double y, int c, int r, DemHit& hit) const {
    const bool t0 = s_->triangle_valid(c, r, 0), t1 = s_->triangle_valid(c, r, 1);
    if (!t0 && !t1) return false;
    const glm::dvec2 nw(xy(c, r)), se(xy(c + 1, r + 1));
    for (int which = 0; which < 2; ++which) {
        if (!(which == 0 ? t0 : t1)) continue;
        const glm::dvec2 third(which == 0 ? xy(c, r + 1) : xy(c + 1, r));
        const PlanBary b = which == 0 ? PlanBary(x, y, nw, third, se) : PlanBary(x, y, nw, se, third);
        if (!b.inside()) continue;
        const std::size_t i = s_->index(c, r), cols = std::size_t(s_->cols());
        hit.node[0] = std::uint32_t(i);
        hit.node[1] = std::uint32_t(which == 0 ? i + cols : i + cols + 1);
        hit.node[2] = std::uint32_t(which == 0 ? i + cols + 1 : i + 1);
        hit.bary = glm::vec3(float(1.0 - b.u - b.w), float(b.u), float(b.w));
        hit.cell = std::uint32_t(r) * std::uint32_t(s_->cols() - 1) + std::uint32_t(c);
        return true;
    }
    return false;
}

bool DemDraper::locate(double x, double y, int& c, int& r, DemHit& hit) const {
    // A point well inside a triangle lies within TerrainLocator's tolerance of no other, so that
    // triangle is the answer whichever cell the search below would stop in. On a grid searched by
    // walking, a hint cell first predicts the point's cell from its own corners (the point's
    // coordinates along its column and row edges): the next vertex of a line lies a cell or so
    // away, and one test of the predicted cell's triangles replaces the walk's steps.
    const bool hinted = c >= 0 && r >= 0 && c <= s_->cols() - 2 && r <= s_->rows() - 2;
    if (hinted && s_->walks() && std::isfinite(x) && std::isfinite(y)) {
        const bool found = s_->with_node_xy([&](const auto& xy) {
            const glm::dvec2 o(xy(c, r)), ec = glm::dvec2(xy(c + 1, r)) - o, er = glm::dvec2(xy(c, r + 1)) - o;
            const double det = ec.x * er.y - ec.y * er.x;
            if (!(std::abs(det) > 0.0)) return false;
            const glm::dvec2 d = glm::dvec2(x, y) - o;
            const double u = (d.x * er.y - d.y * er.x) / det, v = (ec.x * d.y - ec.y * d.x) / det;
            if (!(std::abs(u) < 4.0 && std::abs(v) < 4.0)) return false;  // far: the walk's
            const int pc = std::clamp(c + int(std::floor(u)), 0, s_->cols() - 2);
            const int pr = std::clamp(r + int(std::floor(v)), 0, s_->rows() - 2);
            if (!inside_hit(xy, x, y, pc, pr, hit)) return false;
            c = pc, r = pr;
            return true;
        }, &xy_);
        if (found) return true;
    }
    if (!s_->find_cell(x, y, c, r)) return false;
    // Well inside one of the cell's triangles: that one.
    if (s_->with_node_xy([&](const auto& xy) { return inside_hit(xy, x, y, c, r, hit); }, &xy_)) return true;
    // Else TerrainLocator::locate's rule: the first triangle in mesh order whose barycentric
    // coordinates are all >= -1e-7; any such triangle touches the cell's 3 x 3 neighbourhood.
    for (int rr = r - 1; rr <= r + 1; ++rr)
        for (int cc = c - 1; cc <= c + 1; ++cc)
            for (int which = 0; which < 2; ++which)
                if (triangle_hit(x, y, cc, rr, which, 1e-7, hit)) return true;
    return false;
}

// The positions and normals of a hit's three nodes (node, normal): the column and row of its first
// node divided out once, the others' from their offsets (a cell's corners; any other by division).
void DemDraper::corners(const DemHit& hit, glm::vec3 p[3], glm::vec3 n[3]) const {
    s_->with_nodes([&](const auto& node) {
        if constexpr (std::decay_t<decltype(node)>::by_index) {
            for (int k = 0; k < 3; ++k) p[k] = node(hit.node[k]), n[k] = normal(hit.node[k]);
            return;
        }
        const std::uint32_t cols = std::uint32_t(s_->cols()), i0 = hit.node[0];
        const int c0 = int(i0 % cols), r0 = int(i0 / cols);
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = hit.node[k], d = i - i0;
            int c = c0, r = r0;
            if (d == 0) {
            } else if (d == 1) c = c0 + 1;
            else if (d == cols) r = r0 + 1;
            else if (d == cols + 1) c = c0 + 1, r = r0 + 1;
            else c = int(i % cols), r = int(i / cols);
            p[k] = node(c, r, i), n[k] = normal(i);
        }
    }, &xy_);
}

void DemDraper::position_normal(const DemHit& hit, glm::vec3& position, glm::vec3& normal) const {
    glm::vec3 p[3], n[3];
    corners(hit, p, n);
    const PnPatch patch = pn_patch(p[0], p[1], p[2], n[0], n[1], n[2]);
    position = pn_position(patch, hit.bary);
    normal = pn_normal(patch, hit.bary);
}

float DemDraper::height_normal(const DemHit& hit, glm::vec3& normal) const {
    glm::vec3 p[3], n[3];
    corners(hit, p, n);
    return pn_height_normal(p[0], p[1], p[2], n[0], n[1], n[2], hit.bary, normal);
}

void DemDraper::height_normal4(const DemHit hits[4], float z[4], glm::vec3 normal[4]) const {
    glm::vec3 p[4][3], n[4][3], t[4];
    for (int i = 0; i < 4; ++i) corners(hits[i], p[i], n[i]), t[i] = hits[i].bary;
    pn_height_normal4(p, n, t, z, normal);
}

}  // namespace penink
