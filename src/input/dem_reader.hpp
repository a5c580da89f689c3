// Reads a DEM raster with GDAL (GeoTIFF, ESRI ASCII grid, anything GDAL reads) into a Terrain:
// nodata nodes marked invalid; a DEM in geographic coordinates (degrees) projected node by node
// to the standard UTM zone of its centre with GeographicLib (or `utm_zone` when > 0).
// Node = cell centre (GDAL pixel-is-area: centre of cell (c, r) is GT(c+0.5, r+0.5)).
// Rows/columns are flipped where needed so row 0 is north and column 0 west; rotated
// geotransforms are applied in full. Projected CRSs keep their CRS with coordinates scaled to
// metres (a CRS in feet gives metre positions); no CRS = metres in an unknown frame (crs_wkt "").
// Invalid nodes (nodata value, NaN, mask/alpha band 0) keep their x, y and get z = the lowest
// valid elevation times the exaggeration. Any other value beyond +-1e6 (1e30, inf: a nodata
// marker the file does not declare) is an error naming its row and column in the file. Band scale/offset and a "ft"/"US survey foot" unit
// are applied to elevations; otherwise they are taken as metres.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <glm/vec2.hpp>

#include "input/terrain.hpp"

namespace penink {

struct DemOptions {
    double vertical_exaggeration = 1.0;
    int utm_zone = 0;      // force this UTM zone for geographic DEMs (0 = standard zone of centre)
    bool north = true;     // hemisphere for a forced zone
    // Only the elevations (Terrain::z, pos left empty), and for a geographic DEM the projected
    // x, y apart (Terrain::xy): for the drainage build at factor 1, which needs no positions on
    // an affine grid and takes x, y over as they are on a UTM one.
    bool heights_only = false;
    // With heights_only: each row's local x, y (what Terrain::pos.xy would hold, float) handed to
    // this instead of being stored (Terrain::xy stays empty): called once per row, rows in
    // parallel, when the read is done (t holds its heights, flags and georeference). A caller
    // that checks or reduces the x, y holds none of them.
    std::function<void(const Terrain& t, int row, const glm::vec2* xy)> xy_rows = {};
    // With heights_only: no x, y at all (Terrain::xy empty, xy_rows not called; a geographic
    // DEM's GeographicNodeXY makes any node's, geographic_nodes.hpp).
    bool no_xy = false;
    // Bytes the read may take (memory_budget: 0 = the memory the system has available): a DEM
    // whose nodes need more (dem_read_bytes_per_node each) fails before its values are read.
    std::uint64_t max_memory = 0;
};

// Bytes a read holds per node at its peak: the value as read (up to 8), the valid flag (1) and
// the position (12).
constexpr double dem_read_bytes_per_node = 21.0;

// A DEM read a band of rows at a time, for builds that hold a band of it, not the whole (the
// terrain cache's, surface/terrain_cache.hpp): opening it reads every value once, a band at a
// time, for what read_dem finds over the whole DEM (its errors, the same lines in the same order;
// the range of valid elevations, whose lowest the nodata nodes take); rows() then reads any rows
// again. Heights, flags, x, y and georeference are read_dem's with heights_only, bit for bit.
// Memory: a band of rows (values, flags) and GDAL's blocks of it. One thread at a time.
class DemRows {
public:
    // band_rows: rows of a band of the opening pass (0: about 8 MiB of values, in whole rows of
    // the file's blocks). Without `scan`, no opening pass: for a caller that checks the heights it
    // reads against its own record of them (crease_source.hpp) and zeroes the nodata nodes' (the
    // range, which they take, and the values' errors are not known: meta()'s range is empty).
    explicit DemRows(const std::string& path, const DemOptions& options = {}, int band_rows = 0, bool scan = true);
    ~DemRows();
    DemRows(DemRows&&) noexcept;
    // read_dem's Terrain (heights_only) without its arrays: grid, georeference, elevation range,
    // origin, xy_unit; z, valid, pos and xy empty.
    const Terrain& meta() const;
    // Heights (what a heights-only read puts in Terrain::z) and flags of rows [y0, y1), row-major
    // into z and valid ((y1 - y0) * cols each).
    void rows(int y0, int y1, float* z, std::uint8_t* valid);
    // The local x, y of row y's nodes (what DemOptions::xy_rows receives for it), cols of them.
    void xy(int y, glm::vec2* out) const;

private:
    struct State;
    std::unique_ptr<State> s_;
};

// Caps GDAL's block cache at `bytes` unless the user set GDAL_CACHEMAX, for a command that passes
// down a DEM a band of rows at a time and writes a raster strip by strip (penink fill): each block
// is decoded once a pass, so GDAL's default (5 % of the memory) would only hold blocks never read
// again (1.2 GB of a 1e9-node DEM's on a 24 GB machine, where 64 MiB takes no longer).
void limit_gdal_block_cache(std::uint64_t bytes);

// A DEM's size from its header alone (no value read): the nodes' columns and rows.
struct DemSize {
    int cols = 0, rows = 0;
    double nodes() const { return double(cols) * double(rows); }
};

// Opens `path` and reads its size; the errors of read_dem's opening ("no such file", "not a DEM
// raster (GDAL cannot read it)", an ASCII grid declaring more values than its file holds).
DemSize read_dem_size(const std::string& path);

// Throws penink::Error (stage "input", file = path, ExitCode::bad_input) with one line:
// "no such file", "not a DEM raster (GDAL cannot read it)", "DEM has no valid elevation (all
// nodata)", "DEM is too small (WxH nodes; at least 2x2 needed)", "DEM has fewer than 2x2 valid
// nodes (no cell with data at its four corners)", "row R, column C holds V: elevations must lie
// within +-1e6 (mark missing cells with the nodata value)", "cell size must be > 0 (got S)",
// "vertical exaggeration must be
// > 0", "ASCII grid declares WxH values but its N bytes hold at most M", "reading the DEM's
// WxH nodes would need about X of memory, Y available (--max-memory)", "UTM zone must be 1..60 (0 = standard zone), got N", or "DEM cannot be projected to UTM
// zone ZH: <GeographicLib's reason>" (a geographic DEM too far from the zone). GDAL stays silent.
Terrain read_dem(const std::string& path, const DemOptions& options = {});

// For a DEM read without a CRS whose grid looks like longitude/latitude degrees (cell size below
// 0.01 and every node within -180..360 x -90..90): the warning line
// "penink: warning: input: FILE: no CRS and a cell size of S: if these are degrees, add the CRS
// (e.g. a .prj); positions are taken as metres", else "" (positions in metres would put the
// relief some 100,000 times too steep).
std::string missing_crs_warning(const Terrain& t);

}  // namespace penink
