// View-dependent, crack-free level of detail for a terrain grid: a frame of W x H pixels gets a
// triangle mesh whose size follows the image, not the DEM.
//
// Follows Lindstrom & Pascucci 2001, "Visualization of Large Terrains Made Easy" (IEEE Vis), on
// the right-triangle bintree of Evans, Kirkpatrick & Townsend 1997 (RTIN, "Right-Triangulated
// Irregular Networks"): the DEM's cols x rows nodes sit in the top-left corner of a padded square
// of side 2^levels + 1; the square is halved along its NW-SE diagonal and every right triangle is
// split by longest-edge bisection (the midpoint of its hypotenuse). Each grid node is the split
// vertex of the (up to) two triangles sharing that hypotenuse (its "diamond") and carries
//  - error: a bound, in metres of UNEXAGGERATED elevation, on the vertical distance between
//    either diamond triangle and the DEM at every grid node inside it. Built bottom-up in O(N):
//    with delta = h(m) - (h(a) + h(b)) / 2 the split vertex's offset from the hypotenuse,
//    up(m) = max over the 4 child nodes of up + max(0, delta), lo(m) likewise with min, and
//    error = max(up, -lo) (a child triangle's plane differs from its parent's by delta times a
//    barycentric coordinate, so these bounds are rigorous at the nodes, and nested:
//    error(m) >= error(child)). +inf where the triangle must split: a node with a nodata or
//    padding node in its 3x3 neighbourhood, and (by nesting) all its ancestors. Between nodes
//    the full-resolution surface and the coarse plane are both linear on small pieces; the
//    bound is stated (and tested) at the nodes, as in Lindstrom & Pascucci.
//  - radius (radius(c, r), a function of the node's level and one constant, not stored): a plan
//    (x, y) bounding-circle radius in metres, centred on the node, nested
//    (radius(m) >= radius(child) + |m - child|), covering the node's diamond and every
//    descendant: L times the grid-unit radius of the node's level (1 at the finest split nodes,
//    then + the distance to the children at each level), L the plan positions' Lipschitz
//    constant over the grid (the full-resolution triangles' largest singular value, bounded
//    by Gershgorin: the cell side on a square grid; a rigorous bound on curvilinear grids). Plan
//    suffices: a point q under m satisfies |eye - q|^2 = |eye.xy - q.xy|^2 + (eye.z - q.z)^2 >=
//    max(0, |eye.xy - m.xy| - radius)^2 + max(0, eye.z - z_max*e, z_min*e - eye.z)^2 for any
//    vertical exaggeration e, with z_min, z_max the DEM's valid elevation range (stored
//    unexaggerated), and this lower bound keeps the nesting (so activation stays monotone).
// Water (GridNodes::sea_level: nodes drawn at max(z, s)): a pyramid built from nodes with a sea
// level (TerrainLod::sea_level) bounds the clamped DEM itself: flat water needs no triangles, the
// shore and the land as many as they would dry. A pyramid built without one can still draw water:
// the clamp can raise a coarse triangle's distance to the clamped DEM by at most
// min((s - z_min)+, (z_max - s)+) (proof at water_error in terrain_lod.cpp), and the selection adds
// that constant to every error, so the bounds stay valid and nested (0 for a DEM wholly above or
// below the sea), at the cost of refining everything near a deep sea floor's depth.
// Tests: TerrainLod.WaterKeepsTheErrorBound, TerrainLod.PyramidBuiltWithTheSeaLevelSkipsTheSeaFloor.
// A node is active (its triangles split) when
//     error * e * scale / max(D, near_plane) > tolerance_px   (nearer points are clipped anyway;
//     an orthographic camera: D = 1 and scale = pixels per metre, the same at every depth),
// D the lower bound above, scale = lod_pixel_scale(camera): the focal length in pixels,
// height / (2 tan(vfov / 2)), times 1 + tan^2(hfov/2) + tan^2(vfov/2), the largest magnification
// of a displacement perpendicular to the view ray anywhere in the frame (1 on the axis). No
// cosine of the view angle: a grazing view turns a vertical error into skyline displacement.
// Because error grows and D shrinks from a node to its parents, a node's parents are active
// whenever it is: the selected triangles form a conforming bintree mesh (no T-junctions) for any
// view, which frustum culling only thins (culling drops whole triangles, never changes a split).
//
// Diagonals: RTIN's finest triangles alternate the cell diagonal (a cell (c, r) is split NW-SE
// when (c + r) is even, NE-SW otherwise). Where both halves of a cell are selected (full
// resolution), the cell is emitted as the full-resolution mesh emits it (surface_mesh.hpp: NW-SE,
// triangles {NW, SW, SE}, {NW, SE, NE}, each kept when its three nodes hold data): the cell's
// sides are unchanged, so this stays crack-free, and next to nodata (always refined to full
// resolution) the holes keep the full-resolution outline exactly. A cell at the edge of the
// refined region may keep RTIN's NE-SW diagonal.
// Padding: nodes outside the DEM are invalid; triangles wholly outside are skipped, triangles
// touching them are refined to full resolution and then dropped, so the mesh covers exactly the
// cells the full-resolution mesh covers (a DEM of 2^k + 1 nodes a side needs no padding).
//
// Frames and units: grid node (c, r) is Terrain node (c, r) (row 0 north); positions are the
// Terrain's local metres, z exaggerated as in Terrain::pos (or as GridNodes::at draws them);
// error unexaggerated metres; radius plan metres. Memory: 4 bytes per DEM node (error), held
// in memory or read on demand from the terrain cache (terrain_cache.hpp); built in strips
// (lod_errors), the build holds 4 bytes per node (heights) and the strips besides.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "core/camera.hpp"
#include "input/grid_nodes.hpp"
#include "input/terrain.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

// Built once per DEM, independent of view, light and vertical exaggeration.
struct TerrainLod {
    int cols = 0, rows = 0;      // the DEM grid
    int levels = 0;              // padded side = 2^levels + 1
    // Per DEM node (index(c, r): row-major over cols x rows), metres of elevation, unexaggerated;
    // +inf: must split. The padding nodes of the square (c >= cols or r >= rows) are all +inf
    // (each has padding in its 3x3; the square's corners, no triangle's split vertex, are never
    // asked) and not stored (error_at, padding). Points into `storage` (an
    // array in memory, or a cache file read on demand).
    std::span<const float> error;
    std::shared_ptr<const void> storage;
    // The cache file `error` is read from on demand (array 2, core/checked_blocks.hpp: the
    // selection reads it through a CheckedBlocks::Cached); null: in memory.
    const CheckedBlocks* blocks = nullptr;
    static constexpr int error_array = 2;
    float lipschitz = 0.0f;      // L: the plan positions' Lipschitz constant over the grid, metres per grid unit
    float z_min = 0.0f, z_max = 0.0f;  // range of the valid elevations, metres, unexaggerated
    // The sea level (unexaggerated) whose clamp the errors and range include; -inf: none. Selecting
    // on nodes with another sea level throws std::invalid_argument.
    double sea_level = -std::numeric_limits<double>::infinity();

    int side() const { return (1 << levels) + 1; }
    // Where DEM node (c, r) (c < cols, r < rows) keeps its error.
    std::size_t index(int c, int r) const { return std::size_t(r) * std::size_t(cols) + std::size_t(c); }
    bool padding(int c, int r) const { return c >= cols || r >= rows; }
    // The error of node (c, r) of the padded square (an error held in memory).
    float error_at(int c, int r) const {
        return padding(c, r) ? std::numeric_limits<float>::infinity() : error[index(c, r)];
    }
    // The nested plan radius of node (c, r), metres: L times the grid-unit radius of its level;
    // 0 at the padded square's corners (never split).
    float radius(int c, int r) const;
    // The node lattice (LatticeNode) in `blocks` (array 3: lattice_size(cols) x lattice_size(rows)
    // elements, row-major): lod_lattice_step where the cache holds one, 0 where it holds none (x,
    // y stored rather than derived) or the pyramid is in memory.
    int lattice_step = 0;
    static constexpr int lattice_array = 3;
};

// What the selection reads of a node of the lattice of every lod_lattice_step-th row and column
// (c and r multiples of it), kept together in a terrain cache (terrain_cache.hpp), so that the
// coarse part of a mesh reads the lattice's few blocks rather than blocks of rows r - 1, r and
// r + 1 for each of its vertices and of the pyramid for each node it tests (on a whole view of
// jacksboro refined 29 times, 71 % of the nodes tested and 67 % of the vertices lie on it; the
// rest, near the eye, are close together): the node's error, and the stored heights (GridNodes::pos
// z, unexaggerated) and data flags of the node and of the six neighbours whose full-resolution
// triangles make its vertex normal, neighbour k at (c, r) + lattice_neighbours[k]; a neighbour
// outside the grid: height 0 and no data. valid: bit k set where neighbour k holds data (an
// integer held exactly as a float, so the element is nine floats: block_codec.hpp codes it).
// The x, y of each are the grid's formula's (GridNodes::derive_xy), so a cache that stores x, y
// has no lattice.
inline constexpr int lod_lattice_step = 8;
inline constexpr int lattice_neighbours[7][2] = {{0, 0}, {-1, -1}, {-1, 0}, {0, -1}, {1, 0}, {0, 1}, {1, 1}};
struct LatticeNode {
    float z[7] = {};
    float valid = 0.0f;
    float error = 0.0f;
};
// Lattice nodes along a side of n grid nodes.
inline int lattice_size(int n) { return (n - 1) / lod_lattice_step + 1; }
// Puts grid row r of a cols x rows grid (its heights z and flags v, cols each) in the lattice
// nodes that read it, those of the lattice rows r - 1, r and r + 1 (`lattice`: the whole lattice,
// row-major, lattice_size(cols) a row, made with its elements zero); each grid row once.
void lattice_add_row(int cols, int rows, int r, const float* z, const std::uint8_t* v, LatticeNode* lattice);
// Puts the errors of grid row r (cols of them, TerrainLod::error's) in the lattice nodes of that
// row, when it is a lattice row.
void lattice_add_errors(int cols, int r, const float* e, LatticeNode* lattice);

// The levels of the padded square of a cols x rows grid: the least k with 2^k + 1 >= max(cols, rows).
int lod_padded_levels(int cols, int rows);

// Rows [first, ...) of a DEM's heights and flags, row-major from row `first`.
struct LodRows {
    const float* z = nullptr;
    const std::uint8_t* valid = nullptr;
    int first = 0;
};

// A DEM's heights as the pyramid is built from them: cols x rows nodes, row-major, unexaggerated
// metres (read only where valid), and their valid flags: the whole DEM (z, valid), or rows on
// demand: load(r0, r1) makes rows [r0, r1) readable and says where they are, valid until its
// next call (lod_errors asks for each strip's rows in turn, r0 and r1 never decreasing).
struct LodHeights {
    int cols = 0, rows = 0;
    const float* z = nullptr;
    const std::uint8_t* valid = nullptr;
    std::function<LodRows(int r0, int r1)> load = {};
};

// How lod_errors cuts the work (powers of two). The levels up to squares of fine_side grid units
// are settled in strips of strip_rows padded rows, each loaded with the rows its nodes depend on
// either side (3/2 fine_side + 1: a strip_rows of 512 settles 1.19 times the nodes); the levels
// above on the nodes every fine_side / 2, a grid of (2^levels / (fine_side / 2) + 1)^2 nodes.
// Memory: 13 bytes per padded node of a strip and its margins (side x (strip_rows + 3 fine_side +
// 2)), 4 per padded node of the rows every fine_side (held until the upper levels are settled),
// and 13 per node of the upper levels' grid: 177 MB at a padded side of 16385, where the whole
// square took 14 bytes per padded node (3.8 GB).
struct LodStrips {
    int strip_rows = 512;
    int fine_side = 32;
};

// Padded rows a strip of lod_errors holds (its own and its margins either side); it reads the DEM
// rows among them and one more either side (LodHeights::load).
std::int64_t lod_strip_rows(const LodStrips& strips = {});

// Bytes lod_errors holds for a cols x rows DEM (the strip and its margins, the held rows, the
// upper levels' grid; the formula in LodStrips' comment).
double lod_errors_bytes(int cols, int rows, const LodStrips& strips = {});

// The pyramid's errors (TerrainLod::error, padded row-major) of `dem`, a strip at a time:
// emit(r0, r1, e) receives the final errors of padded rows [r0, r1) ((r1 - r0) * side floats,
// valid during the call); every row once, in no fixed order (the rows holding nodes of the
// levels above fine_side come last). Bit for bit the errors of the whole square settled at once,
// for any strips (tests: TerrainLodStrips.*). Throws std::invalid_argument on strips that are not
// powers of two.
void lod_errors(const LodHeights& dem, const LodStrips& strips, const std::function<void(int, int, const float*)>& emit);

// The DEM's part of padded rows [r0, r1) of errors `e` (side floats a row, as lod_errors emits
// them): the first cols floats of each row r < rows, one row after the other into out
// (TerrainLod::error's layout from row r0); returns how many rows. The padding's are all +inf,
// which TerrainLod does not store (test TerrainLodStrips.BuildTerrainLodKeepsTheWholeSquaresErrors).
int lod_dem_rows(int cols, int rows, int side, int r0, int r1, const float* e, float* out);

// The square of the plan Lipschitz bound (TerrainLod::lipschitz) over the full-resolution
// triangles of the cells between two adjacent rows of `cols` nodes: p, q point at the x of the
// rows' first nodes (row r, row r + 1), y following it, a node every `stride` floats.
float lod_cells_lipschitz2(const float* p, const float* q, int cols, int stride);

// From a Terrain whose pos.z is elevation * t.vertical_exaggeration (divided out: errors are
// unexaggerated). O(N); throws std::invalid_argument on an inconsistent Terrain.
TerrainLod build_terrain_lod(const Terrain& t);
// The same from nodes drawn at `exaggeration` (GridNodes::at), with their sea level, if any.
TerrainLod build_terrain_lod(const GridNodes& nodes, double exaggeration);

struct LodSelection {
    std::size_t triangles = 0, vertices = 0;
    std::size_t active_nodes = 0;  // distinct DEM nodes at which a visited triangle was split
};

// Pixels of image displacement per metre of error at unit distance (see the header comment).
double lod_pixel_scale(const Camera& camera);

// The frame's mesh: triangles counter-clockwise seen from above, vertices only the nodes used
// (compact indices, in order of first use), positions = the DEM nodes' pos (exaggerated, as in
// t), vertex normals = the full-resolution mesh's vertex normal at that node (as
// compute_normals(mesh_from_terrain(t))), face normals of the selected triangles. Triangles
// whose bounding box (plan box of the vertices, z widened by the error bound) lies outside the
// camera frustum are left out, and so are triangles with a nodata node. Errors are multiplied by
// t.vertical_exaggeration. tolerance_px: largest projected vertical error, pixels.
// vertex_nodes (optional): the DEM node index t.index(c, r) of each output vertex.
// Time and memory follow the selected triangles (a top-down traversal with an explicit stack;
// the vertex numbering in a hash table of the nodes visited, none per DEM node).
SurfaceMesh select_lod_mesh(const TerrainLod& lod, const Terrain& t, const Camera& camera, float tolerance_px = 1.0f,
                            LodSelection* stats = nullptr, std::vector<std::uint32_t>* vertex_nodes = nullptr);

struct LodOptions {
    float tolerance_px = 1.0f;  // largest projected vertical error, pixels
    // A size floor: a node whose nested radius projects (at the same distance bound) to at most
    // this many pixels is not split, unless forced (nodata, padding). Radii and that distance
    // are nested like the errors, so the mesh stays crack-free. It caps the triangles of a frame
    // on DEMs rough at the cell scale (cliffs, noise, a DEM far finer than the pixels), where the
    // error test alone refines down to sub-pixel triangles; there the tolerance no longer holds.
    // A split node's radius is about 2.4 times its triangles' half hypotenuse. 0: no floor.
    float min_radius_px = 0.0f;
};

// The same with options.
SurfaceMesh select_lod_mesh(const TerrainLod& lod, const Terrain& t, const Camera& camera, const LodOptions& options,
                            LodSelection* stats = nullptr, std::vector<std::uint32_t>* vertex_nodes = nullptr);
// The same on nodes drawn as GridNodes::at draws them, at `exaggeration` (which scales the errors).
// Nodes and errors of a terrain cache are read one at a time through small caches of blocks
// (NodePointReader, CheckedBlocks::Cached: about 22 MB), none kept in the cache's mapping: a whole
// view of a large DEM touches a few nodes in most blocks, which kept would hold hundreds of MB.
// Those on its node lattice (TerrainLod::lattice_step) are read there, and a node tested alone
// takes its plan position from the grid's formula (GridNodes::derive_xy) where the cache derives
// x, y: the same mesh bit for bit, from fewer blocks.
SurfaceMesh select_lod_mesh(const TerrainLod& lod, const GridNodes& nodes, double exaggeration, const Camera& camera,
                            const LodOptions& options, LodSelection* stats = nullptr,
                            std::vector<std::uint32_t>* vertex_nodes = nullptr);

// The part of the DEM a camera may see, found on the pyramid without visiting every node: the
// grid window (nodes [c0, c1) x [r0, r1)) of the bintree triangles whose boxes (as
// select_lod_mesh culls them: plan box of the corners, z widened by the error bound) meet the
// frustum, splitting only those that cross its boundary, down to triangles min_side grid units
// across; lo, hi bound those boxes (drawn metres). A superset of the visible nodes (by up to
// min_side nodes and the error bounds); an empty window (cols() == 0) when nothing is in view.
// Time and memory follow the frustum's outline, not the DEM.
struct LodView {
    GridWindow window;
    glm::dvec3 lo{0.0}, hi{0.0};
};
LodView lod_visible_window(const TerrainLod& lod, const GridNodes& nodes, double exaggeration, const Camera& camera,
                           int min_side = 16);

}  // namespace penink
