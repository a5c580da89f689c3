// A read-only view of a DEM grid's nodes, wherever they are stored: a Terrain's own arrays, or a
// terrain cache file read on demand (surface/terrain_cache.hpp). cols x rows nodes, row-major,
// row 0 north, in the Terrain's local frame (metres, x east, y north, conventions.md). The drawn (exaggerated) height of a node is its
// stored z times z_scale: 1 for a Terrain read at the drawing's exaggeration, the exaggeration
// for heights stored unexaggerated, computed as the DEM reader computes it (in double, rounded
// once to float). With a sea level (unexaggerated, in the stored z's units) a node below it is
// drawn at it: z = max(z * z_scale, sea_level * z_scale), each rounded once to float, so the water
// is one flat surface hiding the sea floor; the stored z (pos) is unchanged, valid flags too
// (nodata stays nodata). The level-of-detail bound for clamped nodes: terrain_lod.hpp.
// Nodes read from a terrain cache on demand (`blocks`, core/checked_blocks.hpp: array 0 the
// positions, 1 the valid flags) are read when first asked for: at() and has_data() ask for their
// node, and code reading `pos` or `valid` directly asks first (need).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/checked_blocks.hpp"
#include "input/terrain.hpp"

namespace penink {

struct GridNodes {
    int cols = 0, rows = 0;
    const glm::vec3* pos = nullptr;        // cols * rows
    const std::uint8_t* valid = nullptr;   // cols * rows, 1 where the node has data
    double z_scale = 1.0;
    double sea_level = -std::numeric_limits<double>::infinity();  // unexaggerated; -inf: no water
    const CheckedBlocks* blocks = nullptr;  // the cache file pos and valid are read from; null: in memory
    static constexpr int pos_array = 0, valid_array = 1;  // their arrays in `blocks`
    // The heights and flags of every coarse_step-th node of every coarse_step-th row from node
    // (0, 0) (CoarseNode), kept together in `blocks` (array coarse_array, coarse_size(cols) x
    // coarse_size(rows), row-major) where a terrain cache derives x, y: a sampled grid of a step
    // that is a multiple of coarse_step, from such a node, reads them there (read_sampled). 0: none.
    int coarse_step = 0;
    static constexpr int coarse_array = 4;
    int coarse_size(int n) const { return (n - 1) / coarse_step + 1; }
    // The heights and flags of the first and the last column (CoarseNode: column 0's rows, then
    // column cols - 1's) kept together in `blocks` (array edge_array) where a terrain cache derives
    // x, y: read_column reads them there (the automatic camera frames every edge node).
    bool edges_kept = false;
    static constexpr int edge_array = 5;

    // Makes nodes [i0, i1) (positions and valid flags) readable; a no-op for nodes in memory.
    // Throws DamagedBlockError when their blocks are damaged.
    void need(std::size_t i0, std::size_t i1) const {
        if (!blocks) return;
        blocks->need(pos_array, i0, i1);
        blocks->need(valid_array, i0, i1);
    }
    // The nodes of a window (clamped to the grid), row by row.
    void need(GridWindow w) const;
    // The stored positions and valid flags of nodes i0, i0 + every, ... (< i1) into pos and valid
    // ((i1 - i0 + every - 1) / every of each), without keeping the blocks they are read from when
    // these are not yet read (CheckedBlocks::read_strided). Throws DamagedBlockError as need does.
    void read_strided(std::size_t i0, std::size_t i1, std::size_t every, glm::vec3* pos, std::uint8_t* valid) const;
    // The stored heights (z unscaled) of nodes [i0, i1) into z, 0 where a node holds no data, read
    // as read_strided reads (no block kept) without making any derived x, y. `scratch` is the
    // caller's (resized).
    void read_heights(std::size_t i0, std::size_t i1, float* z, std::vector<glm::vec3>& scratch) const;
    // The x, y of nodes first, first + every, ... (count of them) into out[j].x, .y (z left as it
    // is), from the grid's formula without reading a block, where a terrain cache derives them
    // (stores z alone); false, nothing written, where x, y are stored or the nodes are in memory.
    bool derive_xy(std::uint64_t first, std::uint64_t every, std::size_t count, glm::vec3* out) const {
        return blocks && blocks->derive(pos_array, first, every, count, out);
    }
    // The stored positions and flags of column c's nodes (rows of them, row 0 first), read as
    // read_strided reads; the first and last columns from the edge columns where kept (the same
    // values from rows / 128 blocks rather than a block a row).
    void read_column(int c, glm::vec3* pos, std::uint8_t* valid) const;
    // Whether node i holds data.
    bool has_data(std::size_t i) const {
        need(i, i + 1);
        return valid[i] != 0;
    }

    bool has_sea() const { return sea_level > -std::numeric_limits<double>::infinity(); }
    // The drawn height of the water surface (sea_level * z_scale, rounded once to float).
    float sea_z() const { return float(sea_level * z_scale); }
    std::size_t index(int c, int r) const { return std::size_t(r) * std::size_t(cols) + std::size_t(c); }
    std::size_t size() const { return std::size_t(cols) * std::size_t(rows); }
    // Position of node i as drawn.
    glm::vec3 at(std::size_t i) const {
        need(i, i + 1);
        return drawn(pos[i]);
    }
    // A stored position as drawn: z times z_scale, raised to the sea.
    glm::vec3 drawn(glm::vec3 p) const {
        if (z_scale != 1.0) p.z = float(double(p.z) * z_scale);
        if (has_sea() && p.z < sea_z()) p.z = sea_z();
        return p;
    }
    glm::vec3 at(int c, int r) const { return at(index(c, r)); }
};

// A node of GridNodes::coarse_array: its stored height (GridNodes::pos z) and its flag (1: data,
// 0: none) as a float (two floats: block_codec.hpp codes them).
struct CoarseNode {
    float z = 0.0f, valid = 0.0f;
};
inline constexpr int grid_coarse_step = 4;  // the step of the coarse nodes a terrain cache keeps

// Nodes read one at a time (at, has_data: the values GridNodes gives) for scattered reads over a
// whole grid: from a terrain cache, through small caches of decoded blocks
// (CheckedBlocks::Cached, `slots` blocks of positions and as many of valid flags) rather than
// by loading every block touched (a coarse mesh of a large DEM touches a few nodes in most
// blocks); nodes in memory, or in blocks already read, are read in place. One reader per thread.
class NodePointReader {
public:
    explicit NodePointReader(const GridNodes& nodes, std::size_t slots = 4096) : n_(nodes) {
        if (nodes.blocks)
            pos_.emplace(*nodes.blocks, GridNodes::pos_array, slots), valid_.emplace(*nodes.blocks, GridNodes::valid_array, slots);
    }
    glm::vec3 at(std::size_t i) {
        if (!pos_) return n_.at(i);
        glm::vec3 p;
        std::memcpy(&p, pos_->element(i), sizeof p);
        return n_.drawn(p);
    }
    glm::vec3 at(int c, int r) { return at(n_.index(c, r)); }
    bool has_data(std::size_t i) { return valid_ ? *valid_->element(i) != 0 : n_.has_data(i); }

private:
    const GridNodes& n_;
    std::optional<CheckedBlocks::Cached> pos_, valid_;
};

// The nodes of a Terrain as it holds them (z_scale 1). Empty when its arrays do not match its grid.
inline GridNodes grid_nodes(const Terrain& t) {
    if (t.pos.size() != t.size() || t.valid.size() != t.size()) return {};
    return {t.cols, t.rows, t.pos.data(), t.valid.data(), 1.0, -std::numeric_limits<double>::infinity()};
}

// The grid of every step-th node of a window (clamped to the grid) in each direction, from its
// first node: cols x rows nodes, node (i, j) of it node (window.c0 + i step, window.r0 + j step)
// of the grid. step 1: the window's nodes.
struct SampledWindow {
    GridWindow window;
    int step = 1;
    int cols = 0, rows = 0;
};
SampledWindow sampled_window(const GridNodes& nodes, GridWindow w, int step);

// The stored positions (z unscaled, as GridNodes holds them) and valid flags of the sampled nodes
// `part` (in the sampled grid's nodes, inside it), row-major into pos and valid (part.cols() x
// part.rows() of each). Only the grid rows they lie on are read, and of those only the span they
// cover (read_strided: blocks not yet read are not kept, and only the sampled nodes' derived x, y
// are computed), so a step of s reads about 1/s of the part's blocks and holds none of them; rows
// in parallel chunks of at least ~8 K grid nodes. A part read alone gives the values it has in
// the whole (the hachures read their nodes a tile at a time: lines/node_tiles.hpp). Where the
// nodes keep coarse nodes (GridNodes::coarse_step) and the sampled window's first node and step
// fall on them, they are read there (the same values): a step of s then reads about
// (coarse_step / s)^2 / coarse_step of the blocks, a quarter of the others at s = 4.
void read_sampled(const GridNodes& nodes, const SampledWindow& s, GridWindow part, glm::vec3* pos, std::uint8_t* valid);

// A Terrain of the nodes inside `w` (clamped to the grid) as `nodes` draws them, with `grid`'s
// georeference and exaggeration (its own node arrays are not kept); the source offsets moved to w.
Terrain crop_nodes(const Terrain& grid, const GridNodes& nodes, GridWindow w);

}  // namespace penink
