#include "input/terrain.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include <glm/common.hpp>

#include "core/parallel_chunks.hpp"
#include "input/grid_nodes.hpp"

namespace penink {

Terrain crop_terrain(const Terrain& t, GridWindow w) { return crop_nodes(t, grid_nodes(t), w); }

void GridNodes::need(GridWindow w) const {
    if (!blocks) return;
    w = w.clamped(cols, rows);
    if (w.c0 == w.c1) return;
    if (w.c0 == 0 && w.c1 == cols) return need(index(0, w.r0), index(0, w.r1));  // whole rows: one range
    for (int r = w.r0; r < w.r1; ++r) need(index(w.c0, r), index(w.c1 - 1, r) + 1);
}

void GridNodes::read_strided(std::size_t i0, std::size_t i1, std::size_t every, glm::vec3* p, std::uint8_t* v) const {
    every = std::max<std::size_t>(every, 1);
    if (blocks) {
        blocks->read_strided(pos_array, i0, i1, every, p);
        blocks->read_strided(valid_array, i0, i1, every, v);
        return;
    }
    for (std::size_t i = i0; i < i1; i += every) *p++ = pos[i], *v++ = valid[i];
}

namespace {

// n nodes kept as CoarseNode (elements begin, begin + every, ... of array k of nodes.blocks), the
// grid's nodes first, first + node_every, ...: their x, y derived, heights and flags as kept.
void read_kept_nodes(const GridNodes& nodes, int k, std::uint64_t begin, std::uint64_t every, std::uint64_t first,
                     std::uint64_t node_every, std::size_t n, glm::vec3* p, std::uint8_t* v, std::vector<CoarseNode>& kept) {
    kept.resize(n);
    nodes.blocks->read_strided(k, begin, begin + (n - 1) * every + 1, every, kept.data());
    nodes.derive_xy(first, node_every, n, p);
    for (std::size_t i = 0; i < n; ++i) p[i].z = kept[i].z, v[i] = kept[i].valid != 0.0f;
}

}  // namespace

void GridNodes::read_column(int c, glm::vec3* p, std::uint8_t* v) const {
    if (!(blocks && edges_kept && (c == 0 || c == cols - 1))) {
        read_strided(index(c, 0), size(), std::size_t(cols), p, v);
        return;
    }
    std::vector<CoarseNode> column;
    read_kept_nodes(*this, edge_array, c == 0 ? 0 : std::uint64_t(rows), 1, index(c, 0), std::uint64_t(cols),
                    std::size_t(rows), p, v, column);
}

void GridNodes::read_heights(std::size_t i0, std::size_t i1, float* z, std::vector<glm::vec3>& scratch) const {
    if (i0 >= i1) return;
    const std::size_t n = i1 - i0;
    if (!blocks) {
        for (std::size_t i = i0; i < i1; ++i) *z++ = valid[i] ? pos[i].z : 0.0f;
        return;
    }
    scratch.resize(n + (n + sizeof(glm::vec3) - 1) / sizeof(glm::vec3));  // the positions, then the flags
    auto* flags = reinterpret_cast<std::uint8_t*>(scratch.data() + n);
    blocks->read_strided(pos_array, i0, i1, 1, scratch.data(), false);
    blocks->read_strided(valid_array, i0, i1, 1, flags);
    for (std::size_t k = 0; k < n; ++k) z[k] = flags[k] ? scratch[k].z : 0.0f;
}

SampledWindow sampled_window(const GridNodes& nodes, GridWindow w, int step) {
    SampledWindow s;
    s.step = std::max(step, 1);
    s.window = w.clamped(nodes.cols, nodes.rows);
    if (s.window.c0 == s.window.c1 || s.window.r0 == s.window.r1) return s;
    s.cols = (s.window.cols() - 1) / s.step + 1, s.rows = (s.window.rows() - 1) / s.step + 1;
    return s;
}

void read_sampled(const GridNodes& nodes, const SampledWindow& s, GridWindow part, glm::vec3* pos, std::uint8_t* valid) {
    if (part.c0 >= part.c1 || part.r0 >= part.r1) return;
    const std::size_t step = std::size_t(s.step), cols = std::size_t(part.cols());
    const int c0 = s.window.c0 + part.c0 * s.step, c_last = s.window.c0 + (part.c1 - 1) * s.step;
    // rows of at least ~8 K grid nodes a chunk: a tile of the hachures' (64 rows of 256 sampled
    // nodes) on up to 4 threads, a few nodes on the calling one
    const std::size_t min_rows = std::max<std::size_t>(1, (std::size_t(1) << 13) / (cols * step));
    const int cs = nodes.coarse_step;
    if (nodes.blocks && cs > 0 && s.step % cs == 0 && s.window.c0 % cs == 0 && s.window.r0 % cs == 0) {
        const std::size_t coarse_cols = std::size_t(nodes.coarse_size(nodes.cols)), every = std::size_t(s.step / cs);
        parallel_chunks(std::size_t(part.rows()), min_rows, [&](std::size_t j0, std::size_t j1) {
            std::vector<CoarseNode> row;
            for (std::size_t j = j0; j < j1; ++j) {
                const int r = s.window.r0 + (part.r0 + int(j)) * s.step;
                read_kept_nodes(nodes, GridNodes::coarse_array, std::size_t(r / cs) * coarse_cols + std::size_t(c0 / cs),
                                every, nodes.index(c0, r), step, cols, pos + j * cols, valid + j * cols, row);
            }
        });
        return;
    }
    parallel_chunks(std::size_t(part.rows()), min_rows, [&](std::size_t j0, std::size_t j1) {
        for (std::size_t j = j0; j < j1; ++j) {
            const int r = s.window.r0 + (part.r0 + int(j)) * s.step;
            nodes.read_strided(nodes.index(c0, r), nodes.index(c_last, r) + 1, step, pos + j * cols, valid + j * cols);
        }
    });
}

Terrain crop_nodes(const Terrain& grid, const GridNodes& nodes, GridWindow w) {
    w = w.clamped(nodes.cols, nodes.rows);
    nodes.need(w);
    Terrain out = grid;
    out.cols = w.cols(), out.rows = w.rows();
    out.source_col0 = grid.source_col0 + w.c0, out.source_row0 = grid.source_row0 + w.r0;
    out.z = {}, out.xy = {};
    out.pos.resize(out.size()), out.valid.resize(out.size());
    for (int r = 0; r < out.rows; ++r)
        for (int c = 0; c < out.cols; ++c) {
            const std::size_t i = nodes.index(w.c0 + c, w.r0 + r), o = out.index(c, r);
            out.pos[o] = nodes.at(i), out.valid[o] = nodes.valid[i];
        }
    return out;
}

Terrain terrain_metadata(Terrain& t) {
    std::vector<glm::vec3> pos = std::move(t.pos);
    std::vector<std::uint8_t> valid = std::move(t.valid);
    std::vector<float> z = std::move(t.z);
    NodeXY xy = std::move(t.xy);
    Terrain meta = t;
    t.pos = std::move(pos), t.valid = std::move(valid), t.z = std::move(z), t.xy = std::move(xy);
    return meta;
}

glm::dvec2 affine_node_world(const std::array<double, 6>& gt, double unit, int c, int r) {
    const double x = c + 0.5, y = r + 0.5;
    return {(gt[0] + x * gt[1] + y * gt[2]) * unit, (gt[3] + x * gt[4] + y * gt[5]) * unit};
}

glm::vec2 affine_node_xy(const AffineNodes& a, glm::dvec2 origin, int c, int r) {
    return glm::vec2(affine_node_world(a.gt, a.unit, c + a.col0, r + a.row0) - origin);
}

bool terrain_affine(const Terrain& t, AffineNodes& out) {
    if (!(t.xy_unit > 0.0)) return false;
    out = {t.geotransform, t.xy_unit, t.source_col0, t.source_row0};
    return true;
}

bool terrain_bounds(const Terrain& t, glm::dvec3& lo, glm::dvec3& hi) {
    // Floats compared as stored (exact), widened to double once at the end.
    glm::vec3 l(std::numeric_limits<float>::infinity()), h(-std::numeric_limits<float>::infinity());
    bool any = false;
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (!t.valid[i]) continue;
        l = glm::min(l, t.pos[i]), h = glm::max(h, t.pos[i]);
        any = true;
    }
    if (any) lo = glm::dvec3(l), hi = glm::dvec3(h);
    return any;
}

}  // namespace penink
