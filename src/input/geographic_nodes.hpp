// The local x, y of a geographic DEM's nodes, as the DEM reader computes them (dem_reader.cpp),
// so that a cache can recompute them instead of storing them: node (c, r)'s longitude and
// latitude are the source geotransform at its centre (c + 0.5, r + 0.5) times the angular unit
// (degrees per CRS unit), the prime meridian's longitude added to the longitude; they are
// projected to UTM/UPS (zone, hemisphere) by UtmRowProjector in its lattice form over the whole
// source grid (utm_projection.hpp: every 16th node exact, cubic between), the local origin is
// subtracted (double) and the result rounded to float. The same functions in the same order on
// both sides: the x, y come back bit for bit.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "core/big_allocator.hpp"
#include "input/terrain.hpp"
#include "input/utm_projection.hpp"

namespace penink {

struct GeographicNodes {
    std::array<double, 6> gt{0, 1, 0, 0, 0, -1};  // source geotransform (row 0 north)
    double unit = 1.0, meridian = 0.0;           // degrees per CRS unit; prime meridian, degrees east
    int cols = 0, rows = 0;                      // the source grid (the lattice spans it)
    int zone = 0;
    bool north = true;
};

// (longitude, latitude) in degrees of node (c, r).
glm::dvec2 geographic_node_lonlat(const GeographicNodes& g, int c, int r);

// The projector of g's rows to UTM/UPS easting, northing (metres). Throws
// GeographicLib::GeographicErr when a lattice node cannot be projected in g's zone.
UtmRowProjector geographic_projector(const GeographicNodes& g);

// A Terrain's geographic grid: true when t was read from a geographic DEM and projected to UTM
// (source_geographic, utm_zone > 0) and is the whole source grid (source_col0, source_row0 0).
bool terrain_geographic(const Terrain& t, GeographicNodes& out);

// Local float x, y of a world point (metres) relative to `origin`: Terrain::pos.xy.
inline glm::vec2 local_xy(glm::dvec2 world, glm::dvec2 origin) { return glm::vec2(world - origin); }

// Local x, y of nodes c0 .. c1 - 1 of row r (out: c1 - c0), as the DEM reader stores them in
// Terrain::pos when it read the whole grid of g. Built once (projects the lattice), then used
// from any thread.
class GeographicNodeXY {
public:
    GeographicNodeXY(const GeographicNodes& g, glm::dvec2 origin) : rows_(geographic_projector(g)), origin_(origin) {}
    void span(int r, int c0, int c1, glm::vec2* out) const { span(r, c0, c1, 1, out); }
    // The projection's lattice of exact nodes (UtmRowProjector::lattice, adopt_lattice).
    const UtmRowProjector& projector() const { return rows_; }
    // Every `every`-th node of the span from c0 (UtmRowProjector::row_span); out: (c1 - c0 + every - 1) / every.
    void span(int r, int c0, int c1, int every, glm::vec2* out) const;

    glm::dvec2 origin() const { return origin_; }

private:
    UtmRowProjector rows_;
    glm::dvec2 origin_;
};

// The x, y of the nodes of a GeographicNodeXY's rows 0 .. rows - 1 from every row's samples held
// (UtmRowProjector::row_samples: every 16th node of the row, 16 B each; on jacksboro refined 29
// times 117 MB for 11687 x 9976 nodes, which take 933 MB as floats): at(c, r) is span's node
// (c, r), the same floats, for a cubic of four samples, nothing projected. Made on all cores;
// then read from any thread. Only where the projector interpolates (possible()).
class NodeXYRows {
public:
    static bool possible(const GeographicNodeXY& xy) { return xy.projector().sample_count() >= 4; }
    NodeXYRows(std::shared_ptr<const GeographicNodeXY> xy, int rows);
    glm::vec2 at(int c, int r) const {
        const glm::dvec2 p = rows_->node_from_samples(c, samples_.data() + std::size_t(r) * n_) - origin_;
        // rounded to floats for certain: GCC 12 at -O2 drops the rounding of a glm::vec2 made
        // from a glm::dvec2 and widened again (glm::dvec2(glm::vec2(p)) compiles to p), which
        // a caller widening this node's x, y (grid_xy) would otherwise see unrounded
        float x = float(p.x), y = float(p.y);
        asm("" : "+r"(x), "+r"(y));
        return {x, y};
    }
    std::size_t bytes() const { return samples_.size() * sizeof(glm::dvec2); }

private:
    std::shared_ptr<const GeographicNodeXY> xy_;
    const UtmRowProjector* rows_;  // xy_'s
    glm::dvec2 origin_;            // xy_'s
    std::size_t n_ = 0;            // samples a row
    std::vector<glm::dvec2, UninitAllocator<glm::dvec2>> samples_;
};

}  // namespace penink
