// The PN-triangle surface (Vlachos et al., "Curved PN Triangles") of a full-resolution DEM grid,
// evaluated under plan points without a mesh of the DEM: the surface of mesh_from_terrain
// (surface_mesh.hpp: each cell split along its NW-SE diagonal into (NW, SW, SE) and (NW, SE, NE),
// a triangle present when its three nodes hold data; vertex normal = normalised sum of the unit
// normals of the incident triangles) and of TerrainLocator's lookup (terrain_locator.hpp), bit
// for bit: the cell under a point is found from the grid (the inverse of the affine node formula,
// input/terrain.hpp, or a walk over a curvilinear grid), the containing triangle is the first in
// mesh order (row-major cells, (NW, SW, SE) first) within the locator's tolerance, and the normals
// of its three nodes are summed from their incident triangles in mesh order. Used to drape the
// creases and ridges once when the drainage database is built (draped_lines.hpp).
// Frame: the Terrain's local metres (x east, y north, z elevation as the grid holds it: the drainage
// build uses unexaggerated heights).
#pragma once
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/big_allocator.hpp"
#include "drainage/drainage_grid.hpp"
#include "input/terrain.hpp"

namespace penink {

// A view of a DEM grid's nodes (row 0 north): elevations and validity, and x, y either from the
// affine node formula (affine_node_xy, exactly what the DEM reader stores) or per node, plus the
// vertex normal of every node (12 B a node, made on all cores; or, with Normals::on_demand, each
// made where a draper needs it, each DemDraper keeping those of a 64 x 64 window of nodes and the
// faces they were summed from: the ridges of /tmp/j10.tif draped in 0.5-0.9 s instead of 1.8-2.7 s,
// and `penink drainage`'s peak 781 -> 615 MB; where x, y are made from the grid's rows' samples,
// each DemDraper keeps those of a 64 x 64 window too: the crease tiles of a cold render of
// jacksboro x29 then take 4-6 % more CPU than from x, y held whole, not 16 %). Holds
// pointers into the grid or Terrain it was made from, which must outlive it.
class DemSurface {
public:
    // Its vertex normals made for every node at once (12 B a node), or each where asked for
    // (node_normal: the same floats; for lines that touch few of the nodes, as the ridges do).
    enum class Normals { all, on_demand };
    // The full-resolution DEM of a drainage grid: at factor 1 the grid itself (g.z, g.valid, x, y
    // as grid_xy gives them), at factor > 1 its coarse nodes (coarse_z, coarse_valid, coarse_xy).
    explicit DemSurface(const DrainageGrid& g, Normals normals = Normals::all);
    // A Terrain with positions (Terrain::pos; z as stored there).
    explicit DemSurface(const Terrain& t);

    int cols() const { return cols_; }
    int rows() const { return rows_; }
    bool valid(std::size_t i) const { return valid_[i] != 0; }
    glm::vec3 node(int c, int r) const {
        const std::size_t i = index(c, r);
        if (pos_) return pos_[i];
        const glm::vec2 p = node_xy(c, r);
        if (node_blocks_) node_blocks_->need(i);
        return {p.x, p.y, z_[i]};
    }
    glm::vec2 node_xy(int c, int r) const {
        const std::size_t i = index(c, r);
        if (pos_) return glm::vec2(pos_[i]);
        if (xy_) {
            if (node_blocks_) node_blocks_->need(i);
            return xy_[i];
        }
        if (xy_rows_) return xy_rows_->at(c, r);
        if (!col_x_.empty()) return {col_x_[std::size_t(c)], row_y_[std::size_t(r)]};
        return affine_node_xy(nodes_, origin_, c, r);
    }
    std::size_t index(int c, int r) const { return std::size_t(r) * std::size_t(cols_) + std::size_t(c); }
    // The unit vertex normal of node (c, r) as compute_normals gives it ((0, 0, 1) in no triangle):
    // made for every node (Normals::all), or by node_normal each time (DemDraper keeps those it
    // made last).
    glm::vec3 normal(int c, int r) const { return normal(index(c, r)); }
    glm::vec3 normal(std::size_t i) const { return normals_.empty() ? node_normal(i) : normals_[i]; }  // i = index(c, r)
    bool normals_made() const { return !normals_.empty() || cols_ * rows_ == 0; }
    glm::vec3 node_normal(std::size_t i) const;
    // Face normals kept by a caller (a DemDraper's): one slot per triangle of a 64 x 64 window of
    // cells (by column and row mod 64), holding the last face made there and its key.
    struct FaceNormals {
        std::vector<std::pair<std::uint64_t, glm::vec3>> slots;  // key: 2 cell index + which + 1; 0: none
    };
    // Node x, y made from the grid's rows' samples (RowsXY: a cubic of four each), kept by a caller
    // (a DemDraper's): one slot per node of a 64 x 64 window (column and row mod 64), the last made
    // there and its node's index.
    struct NodeXYCache {
        std::vector<std::pair<std::uint64_t, glm::vec2>> slots;  // key: node index + 1; 0: none
    };
    // node_normal of node (c, r), the faces taken from `faces` where kept there and kept there
    // where made: the same floats (each face is made by face_normal alone, and the sum is of the
    // same faces in the same order), with a face shared by a node's neighbours made once.
    glm::vec3 node_normal(int c, int r, FaceNormals& faces, NodeXYCache* cache = nullptr) const;
    // Triangle `which` of cell (c, r) (0: NW, SW, SE; 1: NW, SE, NE) is part of the surface: the
    // cell lies on the grid and the triangle's three nodes hold data.
    bool triangle_valid(int c, int r, int which) const {
        if (c < 0 || r < 0 || c > cols_ - 2 || r > rows_ - 2) return false;
        const std::size_t a = index(c, r), d = index(c + 1, r + 1);
        return valid_[a] && valid_[d] && valid_[which == 0 ? a + std::size_t(cols_) : a + 1];
    }

    // A cell (c, r) whose quadrilateral holds (x, y) within a tolerance, searched from (c, r) as
    // given (a hint: -1 for none); false when the point lies off the grid.
    bool find_cell(double x, double y, int& c, int& r) const;
    // Whether find_cell walks over the grid's cells (its nodes do not follow the affine formula
    // it inverts directly).
    bool walks() const { return !affine_; }

    // Calls f(nodes) with `nodes(c, r)` giving node_xy(c, r) (the same floats), made for the way
    // this surface holds its nodes (per node, by column and row, or the affine formula) so that a
    // loop over many nodes does not choose it at every node; returns what f returns. With a cache,
    // nodes made from row samples are taken from it where kept and kept there where made.
    template <class F> decltype(auto) with_node_xy(F&& f, NodeXYCache* cache = nullptr) const {
        if (pos_) return f(PosXY{pos_, std::size_t(cols_)});
        if (xy_) return f(StoredXY{xy_, std::size_t(cols_), node_blocks_});
        if (xy_rows_ && cache) {
            if (cache->slots.empty()) cache->slots.assign(64 * 64, {0, glm::vec2(0.0f)});
            return f(CachedRowsXY{xy_rows_, cache->slots.data(), std::size_t(cols_)});
        }
        if (xy_rows_) return f(RowsXY{xy_rows_});
        if (!col_x_.empty()) return f(AxisXY{col_x_.data(), row_y_.data()});
        return f(FormulaXY{&nodes_, origin_});
    }
    // The same for node(c, r) given its index i = index(c, r) too.
    template <class F> decltype(auto) with_nodes(F&& f, NodeXYCache* cache = nullptr) const {
        return with_node_xy([&](const auto& xy) { return f(Nodes<std::decay_t<decltype(xy)>>{xy, z_, pos_, node_blocks_}); },
                            cache);
    }

    // node_xy's ways (with_node_xy).
    struct PosXY {
        const glm::vec3* pos;
        std::size_t cols;
        glm::vec2 operator()(int c, int r) const { return glm::vec2(pos[std::size_t(r) * cols + std::size_t(c)]); }
    };
    struct StoredXY {
        const glm::vec2* xy;
        std::size_t cols;
        CellBlocks* blocks;  // where xy and z hold only the blocks filled (DrainageGrid::node_blocks)
        glm::vec2 at(std::size_t i) const {
            if (blocks) blocks->need(i);
            return xy[i];
        }
        glm::vec2 operator()(int c, int r) const { return at(std::size_t(r) * cols + std::size_t(c)); }
    };
    struct RowsXY {
        const NodeXYRows* rows;
        glm::vec2 operator()(int c, int r) const { return rows->at(c, r); }
    };
    struct CachedRowsXY {
        const NodeXYRows* rows;
        std::pair<std::uint64_t, glm::vec2>* slots;  // NodeXYCache's
        std::size_t cols;
        glm::vec2 operator()(int c, int r) const {
            auto& slot = slots[std::size_t(c & 63) + std::size_t(r & 63) * 64];
            const std::uint64_t key = std::uint64_t(r) * cols + std::uint64_t(c) + 1;
            if (slot.first != key) slot = {key, rows->at(c, r)};
            return slot.second;
        }
    };
    struct AxisXY {
        const float *x, *y;
        glm::vec2 operator()(int c, int r) const { return {x[std::size_t(c)], y[std::size_t(r)]}; }
    };
    struct FormulaXY {
        const AffineNodes* nodes;
        glm::dvec2 origin;
        glm::vec2 operator()(int c, int r) const { return affine_node_xy(*nodes, origin, c, r); }
    };
    template <class XY> struct Nodes {
        XY xy;
        const float* z;
        const glm::vec3* pos;
        CellBlocks* blocks;  // where z holds only the blocks filled (DrainageGrid::node_blocks)
        // node i read without its column and row (per-node x, y)
        static constexpr bool by_index = std::is_same_v<XY, PosXY> || std::is_same_v<XY, StoredXY>;
        // (x, y and z of a node held by blocks are in the same block: one need for both)
        glm::vec3 operator()(std::size_t i) const {
            if constexpr (std::is_same_v<XY, PosXY>) return pos[i];
            else {
                if (blocks) blocks->need(i);
                const glm::vec2 p = blocks == xy.blocks ? xy.xy[i] : xy.at(i);
                return {p.x, p.y, z[i]};
            }
        }
        glm::vec3 operator()(int c, int r, std::size_t i) const {
            if constexpr (std::is_same_v<XY, PosXY>) return pos[i];
            else if constexpr (std::is_same_v<XY, StoredXY>) return (*this)(i);
            else {
                const glm::vec2 p = xy(c, r);
                if (blocks) blocks->need(i);
                return {p.x, p.y, z[i]};
            }
        }
    };

private:
    int cols_ = 0, rows_ = 0;
    const std::uint8_t* valid_ = nullptr;
    const float* z_ = nullptr;           // with x, y from xy_ or the affine formula
    const glm::vec3* pos_ = nullptr;     // or x, y, z per node
    const glm::vec2* xy_ = nullptr;
    const NodeXYRows* xy_rows_ = nullptr;  // or the grid's rows' samples (DrainageGrid::xy_rows)
    CellBlocks* node_blocks_ = nullptr;  // the grid's, where xy_ and z_ hold only the blocks filled
    bool affine_ = false;
    AffineNodes nodes_;
    glm::dvec2 origin_{0.0};
    std::vector<float> col_x_, row_y_;  // affine without rotation terms: x by column, y by row
    double inv_[4] = {0, 0, 0, 0};     // inverse of the affine grid's 2x2 part (source units)
    std::vector<glm::vec3, UninitAllocator<glm::vec3>> normals_;

    void make_normals();

    bool affine_guess(double x, double y, int& c, int& r) const;
};

// Where a plan point lies on the DEM's PN surface: its triangle (node indices in mesh order) and
// barycentric weights, as TerrainLocator::locate gives them.
struct DemHit {
    std::uint32_t node[3] = {0, 0, 0};
    glm::vec3 bary{0.0f};
    std::uint32_t cell = 0;  // the triangle's cell (c + r * (cols - 1))
};

// Evaluates the PN surface of a DemSurface (from any number of threads).
class DemDraper {
public:
    explicit DemDraper(const DemSurface& s);
    // The triangle holding (x, y) (the first in mesh order within TerrainLocator's tolerance);
    // `c`, `r`: a cell near the point when known (-1 otherwise), set to the cell found. False off
    // the surface (outside the grid or where no triangle holds data).
    bool locate(double x, double y, int& c, int& r, DemHit& hit) const;
    // PN position and unit normal at a hit (TerrainLocator::pn_position_normal_at).
    void position_normal(const DemHit& hit, glm::vec3& position, glm::vec3& normal) const;
    // position_normal's z (returned) and normal, the same floats (pn_height_normal).
    float height_normal(const DemHit& hit, glm::vec3& normal) const;
    // height_normal of four hits at once (z[i], normal[i] of hits[i]; pn_height_normal4), the
    // same floats.
    void height_normal4(const DemHit hits[4], float z[4], glm::vec3 normal[4]) const;

private:
    const DemSurface* s_;
    // the normals node_normal made last, by node (a surface with Normals::on_demand): one slot a
    // node of a 64 x 64 window (column and row mod 64), and the faces they were summed from
    mutable std::vector<std::pair<std::uint32_t, glm::vec3>> made_;
    mutable DemSurface::FaceNormals faces_;
    mutable DemSurface::NodeXYCache xy_;  // the nodes' x, y made last, where made from row samples
    glm::vec3 normal(std::uint32_t i) const;
    bool triangle_hit(double x, double y, int c, int r, int which, double eps, DemHit& hit) const;
    void corners(const DemHit& hit, glm::vec3 p[3], glm::vec3 n[3]) const;
    template <class XY> bool inside_hit(const XY& xy, double x, double y, int c, int r, DemHit& hit) const;
};

}  // namespace penink
