// The regular grid the drainage network is computed on: fine nodes (cols x rows, row 0 north) with
// an elevation z (local metres, world frame of the Terrain) and a valid mask. It is the PN-triangle
// surface (Vlachos et al. 2001) of the Terrain resampled `factor` times finer in grid index space
// (Mower, "Concurrent Drainage Network Rendering" resamples a 50 m DEM at 10 m); node (fc, fr) lies at coarse index (fc/f, fr/f).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/cell_blocks.hpp"
#include "input/geographic_nodes.hpp"
#include "input/terrain.hpp"

namespace penink {

struct DrainageGrid {
    int cols = 0, rows = 0;           // fine nodes
    int factor = 1;                   // fine nodes per coarse cell side
    std::vector<float> z;             // cols*rows elevations, row-major, local metres
    std::vector<std::uint8_t> valid;  // 1 where the node lies on a valid surface triangle
    double dx = 1.0, dy = 1.0;        // mean fine spacing east (column step) / south (row step), m
    glm::dvec2 origin{0.0};           // projected easting/northing of local (0, 0)
    // Coarse nodes the x, y positions are interpolated from (the Terrain's node x, y and mask);
    // coarse_xy is left empty at factor 1 on an affine grid, where grid_xy computes them, and
    // coarse_valid may be (resample_pn_releasing, decode_crease_source), where valid is the same mask.
    // coarse_z: the Terrain's node elevations at factor > 1 (empty at factor 1, where z is
    // theirs): with coarse_xy and coarse_valid the full-resolution DEM the creases and ridges are
    // draped on (dem_surface.hpp).
    int coarse_cols = 0, coarse_rows = 0;
    NodeXY coarse_xy;
    std::vector<std::uint8_t> coarse_valid;
    std::vector<float> coarse_z;
    // The coarse nodes lie on an affine grid (Terrain::xy_unit > 0): node (c, r)'s x, y is
    // affine_node_xy(affine, origin, c, r), exactly the Terrain's pos.xy.
    bool has_affine = false;
    AffineNodes affine;
    // Where coarse_xy is made again bit for bit: a geographic DEM read whole at factor 1, whose
    // nodes' UTM x, y GeographicNodeXY computes as the DEM reader does (geographic_nodes.hpp).
    // A build lets coarse_xy go while stages that read none of it run (release_node_xy: 8 B a
    // point) and makes it again for those that do (restore_node_xy). Null: coarse_xy is all
    // there is.
    std::shared_ptr<const GeographicNodeXY> node_xy;
    // Where coarse_xy is let go and its nodes are read again (readable_node_xy): node_xy's rows'
    // samples, from which grid_xy and DemSurface make each node's x, y (1 B a node held, not 8).
    std::shared_ptr<const NodeXYRows> xy_rows;
    // Where z or coarse_xy (at factor 1, sized) hold only the blocks of nodes filled so far (z
    // read through NodeHeights, a geographic DEM's x, y made from node_xy, where a render's walks
    // reach: crease_source.hpp): their readers (grid_xy, grid_xy_at, DemSurface, the fall lines'
    // slope field, the stems' walks) ask for each node first (need_node). Null: all there.
    std::shared_ptr<CellBlocks> node_blocks;
    // Where the heights are filled by blocks: their array (cols*rows, not zero-filled first, so
    // its pages are taken only where blocks are filled), z being left empty. Read through
    // node_heights.
    std::shared_ptr<float[]> block_z;

    std::size_t index(int c, int r) const { return std::size_t(r) * cols + c; }
    std::size_t size() const { return std::size_t(cols) * rows; }
};

// A DEM's node heights read where asked for (a render's terrain cache, read by blocks:
// scene/terrain_frames.cpp): span(r, c0, c1, z) writes the heights of nodes c0 .. c1 - 1 of row r
// (unexaggerated, local metres, 0 at nodata: take_node_heights' values) to z. Called from
// several threads at once (CellBlocks fills blocks concurrently).
struct NodeHeights {
    int cols = 0, rows = 0;
    std::function<void(int r, int c0, int c1, float* z)> span;
};

// The fine nodes' heights (cols*rows): z, or block_z where they are filled by blocks.
inline const float* node_heights(const DrainageGrid& g) { return g.block_z ? g.block_z.get() : g.z.data(); }

// Node i's height and x, y made to hold their values where they are filled by blocks
// (DrainageGrid::node_blocks).
inline void need_node(const DrainageGrid& g, std::size_t i) {
    if (g.node_blocks) g.node_blocks->need(i);
}

// Fine grid size for a Terrain and factor: (cols-1)*f+1 by (rows-1)*f+1.
std::size_t resampled_size(const Terrain& t, int factor);

// Samples the PN surface of `t` (vertex normals as in surface_mesh.hpp, cells split NW-SE into
// triangles (a,s,d) and (a,d,b)) at every fine node: z from pn_position, x,y linear on the flat
// triangle (the regular grid for a regular DEM). A node is valid when every triangle vertex with
// a non-zero barycentric weight holds data. factor 1 reproduces the node elevations exactly.
// Throws penink::Error("drainage", t.source, ...) for factor < 1 or a grid under 2x2 nodes.
// A heights-only Terrain (DemOptions::heights_only: pos empty, z set) resamples at factor 1 only
// (else penink::Error "drainage", ExitCode::internal).
DrainageGrid resample_pn(const Terrain& t, int factor);

// resample_pn, then t's positions and heights released (a heights-only t's z becomes the grid's,
// and its xy, where it has them, the grid's coarse_xy).
DrainageGrid resample_pn_releasing(Terrain& t, int factor);
// The z and coarse_xy that resample_pn_releasing(t, 1) gives a heights-only Terrain (its heights,
// 0 at nodata; its nodes' UTM x, y, empty where the affine formula gives them), taken over from
// t without the rest of the grid (masks, spacing); throws as resample_pn does for a heights-only
// Terrain without x, y or an affine grid.
void take_node_arrays(Terrain& t, std::vector<float>& z, NodeXY& xy);
// Its heights alone (z; t.z taken over), 0 at nodata, as take_node_arrays gives them.
void take_node_heights(Terrain& t, std::vector<float>& z);

// Frees g.coarse_xy where g.node_xy makes it again (true); else leaves it (false).
bool release_node_xy(DrainageGrid& g);
// Makes g.coarse_xy again from g.node_xy after release_node_xy (rows in parallel chunks): the
// same floats. Nothing where it is there or cannot be made.
void restore_node_xy(DrainageGrid& g);
// Makes the nodes' x, y readable again after release_node_xy for the stages that read them
// through grid_xy, grid_xy_at and DemSurface: g.xy_rows where node_xy interpolates its rows
// (NodeXYRows::possible: the same floats for an eighth of coarse_xy's memory; kept once made),
// else restore_node_xy.
void readable_node_xy(DrainageGrid& g);

// A grid of hand-given elevations at regular spacing (x = c*spacing, y = -r*spacing), factor 1;
// `valid` empty means all valid. Used by tests and benchmarks.
DrainageGrid make_regular_grid(int cols, int rows, double spacing, std::vector<float> z,
                               std::vector<std::uint8_t> valid = {});

// Local x, y (metres) of fine node (c, r), interpolated like the resampler does (at factor 1 the
// node's own: from the affine grid or coarse_xy).
glm::dvec2 grid_xy(const DrainageGrid& g, int c, int r);

// Local x, y of a point between the fine nodes, (c, r) in fine index units (clamped to the grid):
// at factor > 1 the resampler's interpolation over the coarse triangle (grid_xy at the nodes), at
// factor 1 bilinear between the four nodes around.
glm::dvec2 grid_xy_at(const DrainageGrid& g, double c, double r);

}  // namespace penink
