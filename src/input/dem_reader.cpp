#include "input/dem_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <GeographicLib/UTMUPS.hpp>
#include <glm/common.hpp>
#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel_chunks.hpp"
#include "input/crs_util.hpp"
#include "input/dem_raster.hpp"
#include "input/geographic_nodes.hpp"
#include "input/utm_projection.hpp"

namespace penink {

namespace {

using namespace dem;

constexpr double pi = 3.14159265358979323846;

[[noreturn]] void fail_utm(const std::string& path, int zone, bool north, const GeographicLib::GeographicErr& e) {
    fail(path, "DEM cannot be projected to UTM zone " + std::to_string(zone) + (north ? "N" : "S") + ": " + e.what());
}

// World (projected CRS) coordinates of the nodes, a row at a time: affine_node_world with `unit`,
// or for a geographic DEM the nodes projected to UTM/UPS (geographic_nodes.hpp); lo / hi bound them.
struct WorldXY {
    double unit = 1.0;
    std::optional<UtmRowProjector> utm;
    NodeLonLat lonlat;  // with utm
    glm::dvec2 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};

    void row(const Raster& r, int row, glm::dvec2* out) const {
        if (utm) return utm->row(row, out);
        for (int c = 0; c < r.w; ++c) out[c] = affine_node_world(r.gt, unit, c, row);
    }
    // A row's first or last node (what row() gives there: projected exactly).
    glm::dvec2 row_end(const Raster& r, int c, int row) const {
        return utm ? project_to_utm(lonlat(c, row), utm->zone(), utm->north()) : affine_node_world(r.gt, unit, c, row);
    }
    void take(glm::dvec2 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
};

// lo / hi of every node. On a grid without rotation terms, x along a row and y along a column
// are monotone (affine; UTM easting in longitude at a fixed latitude, northing in latitude at a
// fixed longitude), so the extremes lie on the first and last rows and the rows' ends: only
// those are visited; otherwise every row is.
void bound_nodes(const Raster& r, WorldXY& xy) {
    std::vector<glm::dvec2> line(std::size_t(r.w));
    const bool axis_aligned = r.gt[2] == 0.0 && r.gt[4] == 0.0;
    for (int row = 0; row < r.h; ++row) {
        if (axis_aligned && row != 0 && row != r.h - 1) {
            xy.take(xy.row_end(r, 0, row)), xy.take(xy.row_end(r, r.w - 1, row));
            continue;
        }
        xy.row(r, row, line.data());
        for (const glm::dvec2& p : line) xy.take(p);
    }
}

// Node coordinates in the world CRS (metres) and their bounds; sets crs_wkt, utm_zone, north.
WorldXY world_coordinates(const Raster& r, const DemOptions& options, Terrain& t, const std::string& path) {
    WorldXY w;
    if (r.srs && r.srs->IsGeographic()) {
        const double deg = r.srs->GetAngularUnits(nullptr) * 180.0 / pi;
        const double unit = std::abs(deg - 1.0) < 1e-9 ? 1.0 : deg, meridian = r.srs->GetPrimeMeridian(nullptr);
        t.source_geographic = true;
        GeographicNodes g{r.gt, unit, meridian, r.w, r.h, options.utm_zone, options.north};
        w.lonlat = [g](int c, int row) { return geographic_node_lonlat(g, c, row); };
        const glm::dvec2 centre = 0.5 * (w.lonlat(0, 0) + w.lonlat(r.w - 1, r.h - 1));
        int& zone = g.zone;
        bool& north = g.north;
        try {
            if (zone <= 0) zone = GeographicLib::UTMUPS::StandardZone(centre.y, centre.x), north = centre.y >= 0.0;
            w.utm.emplace(geographic_projector(g));
            bound_nodes(r, w);  // projects every row's ends: a row out of the zone's range fails here
        } catch (const GeographicLib::GeographicErr& e) {
            fail_utm(path, zone, north, e);
        }
        t.utm_zone = zone, t.north = north;
        t.angular_unit = unit, t.prime_meridian = meridian;
        t.crs_wkt = utm_wkt(zone, north);
        return w;
    }
    if (r.srs) {
        int north = 1;
        t.utm_zone = r.srs->GetUTMZone(&north);
        t.north = north != 0;
        t.crs_wkt = srs_wkt(*r.srs);
        w.unit = r.srs->IsProjected() ? r.srs->GetLinearUnits(nullptr) : 1.0;
    }
    bound_nodes(r, w);
    return w;
}

// Some cell between two adjacent rows of w flags has valid nodes at its four corners.
bool valid_cell_between(const std::uint8_t* a, const std::uint8_t* b, std::size_t w) {
    for (std::size_t c = 0; c + 1 < w; ++c)
        if (a[c] && a[c + 1] && b[c] && b[c + 1]) return true;
    return false;
}

// Some cell has valid nodes at its four corners (usually the first few rows show one).
bool has_valid_cell(const Raster& r) {
    const std::size_t w = std::size_t(r.w);
    for (std::size_t row = 0; row + 1 < std::size_t(r.h); ++row)
        if (valid_cell_between(&r.valid[row * w], &r.valid[(row + 1) * w], w)) return true;
    return false;
}

// r: the grid's size and what classifying every value found (range in metres, out_of_range);
// valid_cell: has_valid_cell of its flags.
void check_grid(const Raster& r, bool valid_cell, const std::string& path) {
    if (r.w < 2 || r.h < 2)
        fail(path, "DEM is too small (" + std::to_string(r.w) + "x" + std::to_string(r.h) +
                       " nodes; at least 2x2 needed)");
    if (r.out_of_range != Raster::npos) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "row %zu, column %zu holds %g: elevations must lie within +-1e6 (mark missing cells with "
                      "the nodata value)",
                      r.out_of_range / std::size_t(r.w) + 1, r.out_of_range % std::size_t(r.w) + 1,
                      r.out_of_range_value);
        fail(path, text);
    }
    if (r.emin > r.emax)  // the band pass widened the range at every valid node: none was
        fail(path, "DEM has no valid elevation (all nodata)");
    if (!valid_cell)
        fail(path, "DEM has fewer than 2x2 valid nodes (no cell with data at its four corners)");
}

void check_options(const std::string& path, const DemOptions& options) {
    const double ve = options.vertical_exaggeration;
    if (!std::isfinite(ve) || ve <= 0.0) fail(path, "vertical exaggeration must be > 0");
    if (options.utm_zone < 0 || options.utm_zone > 60)
        fail(path, "UTM zone must be 1..60 (0 = standard zone), got " + std::to_string(options.utm_zone));
}

// What read_dem's Terrain holds before its values: size, exaggeration, source, geotransform.
Terrain terrain_of(const Raster& r, const std::string& path, double ve) {
    Terrain t;
    t.cols = r.w, t.rows = r.h;
    t.vertical_exaggeration = ve;
    t.source = path;
    t.geotransform = r.gt;
    return t;
}

// And after them: the x, y unit of an affine grid and the elevation range (metres).
void finish_terrain(const Raster& r, const WorldXY& xy, Terrain& t) {
    if (!xy.utm) t.xy_unit = xy.unit;  // an affine grid: affine_node_xy gives pos.xy
    t.elevation_min = r.emin, t.elevation_max = r.emax;
}

// Row `row`'s nodes' world coordinates relative to the bounds' rounded centre (t.origin), as
// floats, into `local` (r.w of them); `line` is scratch (r.w).
void row_local_xy(const Raster& r, const WorldXY& xy, const Terrain& t, const std::string& path, int row,
                  glm::dvec2* line, glm::vec2* local) {
    try {
        xy.row(r, row, line);
    } catch (const GeographicLib::GeographicErr& e) {
        fail_utm(path, t.utm_zone, t.north, e);
    }
    for (int c = 0; c < r.w; ++c) local[c] = local_xy(line[c], t.origin);
}

// f(row, x, y of the row's nodes) for every row (row_local_xy); rows in parallel.
template <class F>
void each_row_xy(const Raster& r, const WorldXY& xy, const Terrain& t, const std::string& path, F&& f) {
    parallel_chunks(std::size_t(r.h), rows_per_chunk(r), [&](std::size_t r0, std::size_t r1) {
        std::vector<glm::dvec2> line(std::size_t(r.w));
        std::vector<glm::vec2> local(std::size_t(r.w));
        for (std::size_t row = r0; row < r1; ++row) {
            row_local_xy(r, xy, t, path, int(row), line.data(), local.data());
            f(row, local.data());
        }
    });
}

// f(node index, row, c, x, y) for every node (each_row_xy).
template <class F>
void each_node_xy(const Raster& r, const WorldXY& xy, const Terrain& t, const std::string& path, F&& f) {
    each_row_xy(r, xy, t, path, [&](std::size_t row, const glm::vec2* p) {
        for (int c = 0; c < r.w; ++c) f(row * r.w + c, row, c, p[c].x, p[c].y);
    });
}

// t.pos: each_node_xy's x, y and z the node elevation times the vertical exaggeration.
void fill_positions(const Raster& r, const WorldXY& xy, Terrain& t, const std::string& path) {
    t.pos.resize(std::size_t(r.w) * r.h);
    const double s = t.vertical_exaggeration;
    each_node_xy(r, xy, t, path, [&](std::size_t i, std::size_t row, int c, float x, float y) {
        t.pos[i] = glm::vec3(x, y, float(node_elevation(r, row, c, r.unit, r.emin) * s));
    });
}


// A heights-only read of a geographic DEM: t.xy what fill_positions puts in pos[i].x, y (t.origin
// set).
void fill_xy(const Raster& r, const WorldXY& xy, Terrain& t, const std::string& path) {
    t.xy.resize(std::size_t(r.w) * r.h);
    each_node_xy(r, xy, t, path, [&](std::size_t i, std::size_t, int, float x, float y) { t.xy[i] = glm::vec2(x, y); });
}

}  // namespace

Terrain read_dem(const std::string& path, const DemOptions& options) {
    const QuietGdal quiet;
    check_options(path, options);
    const double ve = options.vertical_exaggeration;
    GDALDatasetUniquePtr ds = open_raster(path);
    Raster r = raster_header(*ds);
    check_memory("input", path, "reading the DEM's " + std::to_string(r.w) + "x" + std::to_string(r.h) + " nodes",
                 double(r.w) * double(r.h) * dem_read_bytes_per_node, memory_budget(options.max_memory));
    Terrain t = terrain_of(r, path, ve);
    // The spatial reference (PROJ's database: ~15 ms), the nodes' bounds and a geographic DEM's
    // UTM x, y here while another thread reads the values, for a GeoTIFF: GDAL's GTiff driver
    // builds the spatial reference when first asked, other drivers (an ASCII grid's .prj) as
    // they open, which a second handle would do again. Errors in the order of a sequential
    // read: the band's, the grid's, then the projection's.
    std::optional<WorldXY> xy;
    std::exception_ptr crs_error;
    const std::string driver = ds->GetDriver()->GetDescription();
    std::vector<float>* heights = options.heights_only ? &t.z : nullptr;
    auto crs = [&] {
        try {
            if (const OGRSpatialReference* s = ds->GetSpatialRef(); s && !s->IsEmpty()) r.srs.reset(s->Clone());
            r.unit = vertical_unit(*ds->GetRasterBand(1));  // from the georeferencing just loaded
            xy.emplace(world_coordinates(r, options, t, path));
            t.origin = glm::round(0.5 * (xy->lo + xy->hi));
            if (heights && xy->utm && !options.xy_rows && !options.no_xy) fill_xy(r, *xy, t, path);
        } catch (...) {
            crs_error = std::current_exception();
        }
    };
    if (driver == "GTiff") {
        run_beside([&] { read_heights(path, driver, r); }, crs);
    } else {
        read_heights(*ds, path, r);
        crs();
    }
    range_to_metres(r);
    check_grid(r, has_valid_cell(r), path);
    if (crs_error) std::rethrow_exception(crs_error);
    finish_terrain(r, *xy, t);
    if (!heights) fill_positions(r, *xy, t, path);
    else take_heights(r, ve, t.z);
    t.valid = std::move(r.valid);
    if (heights && options.xy_rows && !options.no_xy)
        each_row_xy(r, *xy, t, path, [&](std::size_t row, const glm::vec2* p) { options.xy_rows(t, int(row), p); });
    return t;
}

struct DemRows::State {
    std::string path;
    GDALDatasetUniquePtr ds;
    Raster r;  // header, band_info, unit; range in metres
    std::optional<WorldXY> xy;
    Terrain meta;
    Raster rows;  // the last rows read (scratch)
    // rows() reads units of `unit` source rows (whole rows of the file's blocks, so each block is
    // decoded once in a pass down the DEM); `rows` holds our rows [held0, held1) of one
    int unit = 256, held0 = 0, held1 = 0;
};

DemRows::~DemRows() = default;
DemRows::DemRows(DemRows&&) noexcept = default;

DemRows::DemRows(const std::string& path, const DemOptions& options, int band_rows, bool scan)
    : s_(std::make_unique<State>()) {
    const QuietGdal quiet;
    check_options(path, options);
    State& s = *s_;
    s.path = path;
    s.ds = open_raster(path);
    Raster& r = s.r;
    r = raster_header(*s.ds);
    GDALRasterBand& band = *s.ds->GetRasterBand(1);
    band_info(band, r);
    // Whole rows of a tiled or striped file's blocks, each decoded once a pass.
    if (band_rows <= 0) band_rows = dem::band_rows(band, r.w, sizeof(double));
    int block_w = 0, block_h = 0;
    band.GetBlockSize(&block_w, &block_h);
    s.unit = block_h > 1 ? block_h * std::max(1, 256 / block_h) : 256;
    check_memory("input", path,
                 "reading the DEM's " + std::to_string(r.w) + "x" + std::to_string(r.h) + " nodes by bands of " +
                     std::to_string(band_rows) + " rows",
                 double(r.w) * double(band_rows) * dem_read_bytes_per_node, memory_budget(options.max_memory));
    s.meta = terrain_of(r, path, options.vertical_exaggeration);
    std::exception_ptr crs_error;  // reported after the values' errors, as read_dem does
    try {
        if (const OGRSpatialReference* srs = s.ds->GetSpatialRef(); srs && !srs->IsEmpty()) r.srs.reset(srs->Clone());
        r.unit = vertical_unit(band);
        s.xy.emplace(world_coordinates(r, options, s.meta, path));
        s.meta.origin = glm::round(0.5 * (s.xy->lo + s.xy->hi));
    } catch (...) {
        crs_error = std::current_exception();
    }
    if (!scan) {
        if (crs_error) std::rethrow_exception(crs_error);
        finish_terrain(r, *s.xy, s.meta);
        return;
    }
    // Every value once: the range, the first value out of range (source order), a valid cell.
    bool valid_cell = false;
    std::vector<std::uint8_t> last;  // the previous band's last row of flags
    for (int y0 = 0; y0 < r.h; y0 += band_rows) {
        const int y1 = std::min(r.h, y0 + band_rows);
        read_rows(band, r, y0, y1, s.rows, path);
        band.FlushCache();
        r.emin = std::min(r.emin, s.rows.emin), r.emax = std::max(r.emax, s.rows.emax);
        if (s.rows.out_of_range < r.out_of_range)
            r.out_of_range = s.rows.out_of_range, r.out_of_range_value = s.rows.out_of_range_value;
        const std::size_t w = std::size_t(r.w);
        if (!valid_cell && !last.empty()) valid_cell = valid_cell_between(last.data(), s.rows.valid.data(), w);
        if (!valid_cell) valid_cell = has_valid_cell(s.rows);
        last.assign(s.rows.valid.end() - std::ptrdiff_t(w), s.rows.valid.end());
    }
    s.rows = {}, s.held0 = s.held1 = 0;
    range_to_metres(r);
    check_grid(r, valid_cell, path);
    if (crs_error) std::rethrow_exception(crs_error);
    finish_terrain(r, *s.xy, s.meta);
}

const Terrain& DemRows::meta() const { return s_->meta; }

void DemRows::rows(int y0, int y1, float* z, std::uint8_t* valid) {
    const QuietGdal quiet;
    State& s = *s_;
    const Raster& r = s.r;
    if (y0 < 0 || y1 > r.h || y0 > y1) throw std::out_of_range("DemRows::rows: rows outside the DEM");
    if (y0 == y1) return;
    GDALRasterBand& band = *s.ds->GetRasterBand(1);
    const double ve = s.meta.vertical_exaggeration;
    const std::size_t w = std::size_t(r.w);
    for (int y = y0; y < y1;) {
        if (y < s.held0 || y >= s.held1) {  // the unit of source rows holding our row y
            const int k = (r.flip_r ? r.h - 1 - y : y) / s.unit;
            const int a = k * s.unit, b = std::min(r.h, a + s.unit);
            const int o0 = r.flip_r ? r.h - b : a, o1 = r.flip_r ? r.h - a : b;
            s.held0 = s.held1 = 0;  // nothing held should the read fail
            read_rows(band, r, o0, o1, s.rows, s.path);
            band.FlushCache();
            s.held0 = o0, s.held1 = o1;
        }
        const int e = std::min(y1, s.held1);
        const std::size_t from = std::size_t(y - s.held0), to = std::size_t(y - y0);
        parallel_chunks(std::size_t(e - y), rows_per_chunk(r), [&](std::size_t i0, std::size_t i1) {
            for (std::size_t i = i0; i < i1; ++i)
                for (int c = 0; c < r.w; ++c)
                    z[(to + i) * w + std::size_t(c)] = float(node_elevation(s.rows, from + i, c, r.unit, r.emin) * ve);
        });
        std::copy_n(s.rows.valid.begin() + std::ptrdiff_t(from * w), std::size_t(e - y) * w, valid + to * w);
        y = e;
    }
}

void DemRows::xy(int y, glm::vec2* out) const {
    const State& s = *s_;
    thread_local std::vector<glm::dvec2> line;
    line.resize(std::size_t(s.r.w));
    row_local_xy(s.r, *s.xy, s.meta, s.path, y, line.data(), out);
}

void limit_gdal_block_cache(std::uint64_t bytes) {
    if (!CPLGetConfigOption("GDAL_CACHEMAX", nullptr)) GDALSetCacheMax64(GIntBig(bytes));
}

DemSize read_dem_size(const std::string& path) {
    const QuietGdal quiet;
    GDALDatasetUniquePtr ds = open_raster(path);
    return {ds->GetRasterXSize(), ds->GetRasterYSize()};
}

std::string missing_crs_warning(const Terrain& t) {
    if (!t.crs_wkt.empty() || t.source_geographic || t.cols < 1 || t.rows < 1) return "";
    const auto& g = t.geotransform;
    const double cell = std::max(std::hypot(g[1], g[4]), std::hypot(g[2], g[5]));
    if (!(cell > 0.0 && cell < 0.01)) return "";
    for (const double c : {0.0, double(t.cols)})
        for (const double r : {0.0, double(t.rows)}) {  // the grid's corners, source units
            const double x = g[0] + (t.source_col0 + c) * g[1] + (t.source_row0 + r) * g[2];
            const double y = g[3] + (t.source_col0 + c) * g[4] + (t.source_row0 + r) * g[5];
            if (x < -180.0 || x > 360.0 || y < -90.0 || y > 90.0) return "";
        }
    char size[32];
    std::snprintf(size, sizeof size, "%.6g", cell);
    return "penink: warning: input: " + t.source + ": no CRS and a cell size of " + size +
           ": if these are degrees, add the CRS (e.g. a .prj); positions are taken as metres";
}

}  // namespace penink
