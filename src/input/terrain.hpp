// A DEM as a grid of nodes in the world frame (conventions.md): x east, y north, z elevation
// times vertical exaggeration, metres, relative to `origin` (projected CRS coordinates of the
// local frame's origin, so floats keep centimetre precision). Row 0 is the north edge.
// A geographic DEM is projected node by node to UTM, so the grid may be curvilinear.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/big_allocator.hpp"

namespace penink {

// Nodes' local x, y (a geographic DEM's UTM ones), one per node: grown without zero-filling
// (UninitAllocator), so the threads that compute them touch their pages first, in parallel.
using NodeXY = std::vector<glm::vec2, UninitAllocator<glm::vec2>>;

struct Terrain {
    int cols = 0, rows = 0;
    glm::dvec2 origin{0.0};   // projected easting/northing of local (0,0), metres
    std::string crs_wkt;      // WKT of the projected world CRS (UTM for geographic input)
    int utm_zone = 0;         // UTM zone of the world CRS, 0 when it is not UTM
    bool north = true;        // UTM hemisphere
    double vertical_exaggeration = 1.0;
    std::vector<glm::vec3> pos;    // cols*rows node positions, row-major, local metres
    // A heights-only read (DemOptions::heights_only): pos is empty and z holds what pos[i].z would;
    // x, y are affine_node_xy's on an affine grid, else (a geographic DEM) in xy. Empty otherwise.
    std::vector<float> z;
    NodeXY xy;
    std::vector<std::uint8_t> valid;  // 1 where the node has data (not nodata)
    std::string source;       // file it came from (for messages)
    int source_col0 = 0, source_row0 = 0;  // where this grid starts in the source DEM (after cropping)
    // Source raster as read (after flipping to row 0 = north, column 0 = west): the centre of
    // node (c, r) of this grid is geotransform applied to (source_col0 + c + 0.5,
    // source_row0 + r + 0.5), in the source CRS's units (degrees when source_geographic).
    std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
    bool source_geographic = false;
    // source_geographic: degrees per unit of the geotransform and the prime meridian's longitude
    // (degrees east of Greenwich): node longitudes, latitudes as geographic_nodes.hpp gives them.
    double angular_unit = 1.0, prime_meridian = 0.0;
    // > 0: pos.xy of node (c, r) is affine_node_xy(terrain_affine) (a DEM in a projected or no CRS: an affine
    // grid, geotransform in CRS units times xy_unit metres); 0: no such formula (e.g. geographic).
    double xy_unit = 0.0;
    double elevation_min = 0.0, elevation_max = 0.0;  // valid elevations, metres, unexaggerated

    std::size_t index(int c, int r) const { return std::size_t(r) * cols + c; }
    std::size_t size() const { return std::size_t(cols) * rows; }
};

// The affine grid a DEM's nodes lie on: world x, y (metres) of source node (c, r), c counted from
// the west and r from the north after orientation, = geotransform at the node centre times unit.
struct AffineNodes {
    std::array<double, 6> gt{0, 1, 0, 0, 0, -1};
    double unit = 1.0;
    int col0 = 0, row0 = 0;  // source node of this grid's node (0, 0)
    bool operator==(const AffineNodes&) const = default;
};

glm::dvec2 affine_node_world(const std::array<double, 6>& gt, double unit, int c, int r);

// Local x, y (floats, relative to `origin`) of node (c, r) of a grid on `a`: exactly what the
// DEM reader stores in Terrain::pos.
glm::vec2 affine_node_xy(const AffineNodes& a, glm::dvec2 origin, int c, int r);

// The affine grid of t's nodes, when t.xy_unit > 0.
bool terrain_affine(const Terrain& t, AffineNodes& out);

// Node range [c0, c1) x [r0, r1) of a Terrain.
struct GridWindow {
    int c0 = 0, r0 = 0, c1 = 0, r1 = 0;
    int cols() const { return c1 - c0; }
    int rows() const { return r1 - r0; }
    // The window inside a grid of cols x rows nodes (empty where it lies outside).
    GridWindow clamped(int cols, int rows) const {
        GridWindow w;
        w.c0 = std::clamp(c0, 0, cols), w.c1 = std::clamp(c1, w.c0, cols);
        w.r0 = std::clamp(r0, 0, rows), w.r1 = std::clamp(r1, w.r0, rows);
        return w;
    }
};

// Copy of the nodes inside `w` (clamped to the grid); keeps origin and CRS (crop_nodes).
Terrain crop_terrain(const Terrain& t, GridWindow w);

// t's grid and georeference without its node arrays (pos, valid, z, xy): they are set aside, not
// copied, while the rest is, and t is as it was on return.
Terrain terrain_metadata(Terrain& t);

// Axis-aligned bounds of the valid nodes (local metres); false when none is valid.
bool terrain_bounds(const Terrain& t, glm::dvec3& lo, glm::dvec3& hi);

}  // namespace penink
