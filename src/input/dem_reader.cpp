#include "input/dem_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <GeographicLib/UTMUPS.hpp>
#include <glm/common.hpp>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_frmts.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/big_allocator.hpp"
#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "input/crs_util.hpp"
#include "input/utm_projection.hpp"

namespace penink {

namespace {

constexpr double pi = 3.14159265358979323846;

// The band as read: values in source order (float where that holds them exactly: the same
// doubles, half the memory) and their conversion to metres; in our orientation (row 0 north,
// column 0 west) the valid mask and the range of valid elevations (metres).
struct Raster {
    int w = 0, h = 0;
    std::vector<float, BigAllocator<float>> raw_f;  // one of the two holds the values
    std::vector<double, BigAllocator<double>> raw_d;
    double scale = 1.0, offset = 0.0, unit = 1.0;  // metres = (value * scale + offset) * unit
    bool flip_c = false, flip_r = false;
    GDALDataType type = GDT_Unknown;
    std::vector<std::uint8_t> mask;  // source order; empty: none beyond the nodata value
    bool has_nodata = false;
    double nodata = 0.0;
    std::vector<std::uint8_t> valid;
    double emin = std::numeric_limits<double>::max(), emax = -std::numeric_limits<double>::max();
    std::array<double, 6> gt{0, 1, 0, 0, 0, -1};
    std::unique_ptr<OGRSpatialReference> srs;  // null when the dataset has none

    std::size_t source(std::size_t row, int c) const {
        return (flip_r ? std::size_t(h) - 1 - row : row) * std::size_t(w) + std::size_t(flip_c ? w - 1 - c : c);
    }
    double value(std::size_t src) const { return raw_f.empty() ? raw_d[src] : double(raw_f[src]); }
    double metres(double v) const { return (v * scale + offset) * unit; }
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw Error("input", path, what, ExitCode::bad_input);
}

// Keeps GDAL quiet for the lifetime of the guard: our error line is the only message.
struct QuietGdal {
    QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); }
    ~QuietGdal() {
        CPLErrorReset();
        CPLPopErrorHandler();
    }
};

GDALDatasetUniquePtr open_with(const std::string& path, const char* const* drivers) {
    return GDALDatasetUniquePtr(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr)));
}

// A GeoTIFF is opened with GDAL's GTiff driver alone; any other file once every driver is
// registered (GDALAllRegister: ~2 ms, so only when needed).
GDALDatasetUniquePtr open_raster(const std::string& path) {
    VSIStatBufL st;
    if (VSIStatExL(path.c_str(), &st, VSI_STAT_EXISTS_FLAG) != 0) fail(path, "no such file");
    GDALRegister_GTiff();
    const char* const gtiff[] = {"GTiff", nullptr};
    GDALDatasetUniquePtr ds = open_with(path, gtiff);
    if (!ds) GDALAllRegister(), ds = open_with(path, nullptr);
    if (!ds || ds->GetRasterCount() < 1 || ds->GetRasterXSize() < 1 || ds->GetRasterYSize() < 1)
        fail(path, "not a DEM raster (GDAL cannot read it)");
    return ds;
}

// Metres per vertical unit from the band's unit string (metres when unknown or empty).
double vertical_unit(GDALRasterBand& band) {
    const std::string u = band.GetUnitType();
    if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
    if (u == "US survey foot" || u == "ftUS" || u == "us-ft") return 1200.0 / 3937.0;
    return 1.0;
}

bool is_nodata(double v, bool has_nodata, double nodata, GDALDataType type) {
    if (std::isnan(v)) return true;
    if (!has_nodata) return false;
    if (type == GDT_Float32) return float(v) == float(nodata);
    return v == nodata;
}

// The per-dataset or alpha mask of the band (source order), empty when it has none beyond the
// nodata value.
std::vector<std::uint8_t> read_mask(GDALRasterBand& band, const std::string& path) {
    const int flags = band.GetMaskFlags();
    if (flags & (GMF_ALL_VALID | GMF_NODATA)) return {};
    std::vector<std::uint8_t> mask(std::size_t(band.GetXSize()) * band.GetYSize());
    if (band.GetMaskBand()->RasterIO(GF_Read, 0, 0, band.GetXSize(), band.GetYSize(), mask.data(),
                                     band.GetXSize(), band.GetYSize(), GDT_Byte, 0, 0) != CE_None)
        fail(path, "not a DEM raster (GDAL cannot read it)");
    return mask;
}

// Flips the geotransform (and says which axes to flip) so row 0 is north and column 0 west.
void orient(std::array<double, 6>& gt, int w, int h, bool& flip_c, bool& flip_r) {
    flip_c = gt[1] < 0.0;
    flip_r = gt[5] > 0.0;
    if (flip_c) gt = {gt[0] + w * gt[1], -gt[1], gt[2], gt[3] + w * gt[4], -gt[4], gt[5]};
    if (flip_r) gt = {gt[0] + h * gt[2], gt[1], -gt[2], gt[3] + h * gt[5], gt[4], -gt[5]};
}

// Rows per parallel chunk of a per-node loop: chunks of at least 64 K nodes.
std::size_t rows_per_chunk(const Raster& r) { return std::max<std::size_t>(1, 65536 / std::size_t(r.w)); }

// Reads the band as T into r.raw_f / r.raw_d, with its mask, nodata value, scale and offset (not
// its unit: GDAL's GeoTIFF driver builds the spatial reference for that).
template <class T>
void read_band(GDALRasterBand& band, Raster& r, const std::string& path) {
    auto& raw = [&]() -> auto& {
        if constexpr (sizeof(T) == 4) return r.raw_f;
        else return r.raw_d;
    }();
    raw.resize(std::size_t(r.w) * r.h);
    const GDALDataType as = sizeof(T) == 4 ? GDT_Float32 : GDT_Float64;
    if (band.RasterIO(GF_Read, 0, 0, r.w, r.h, raw.data(), r.w, r.h, as, 0, 0) != CE_None)
        fail(path, "not a DEM raster (GDAL cannot read it)");
    r.mask = read_mask(band, path);
    int has = 0, has_scale = 0, has_offset = 0;
    r.nodata = band.GetNoDataValue(&has), r.has_nodata = has != 0;
    const double scale = band.GetScale(&has_scale), offset = band.GetOffset(&has_offset);
    r.scale = has_scale ? scale : 1.0, r.offset = has_offset ? offset : 0.0;
}

// r.valid (from NaN, the nodata value and the mask; a non-finite elevation is invalid too) and
// in r.emin / r.emax the range of the valid values scaled (value * scale + offset, before the
// vertical unit, which GDAL's GeoTIFF driver takes from the spatial reference: so this runs beside
// its build), in one pass over the values read (raw: r.raw_f or r.raw_d). range_to_metres after.
template <class Raw>
void classify_values(Raster& r, const Raw& raw) {
    r.valid.resize(raw.size());
    std::mutex merge;
    parallel_chunks(std::size_t(r.h), rows_per_chunk(r), [&](std::size_t r0, std::size_t r1) {
        double lo = std::numeric_limits<double>::max(), hi = -lo;
        for (std::size_t row = r0; row < r1; ++row)
            for (int c = 0; c < r.w; ++c) {
                const std::size_t src = r.source(row, c);
                const double v = double(raw[src]), e = v * r.scale + r.offset;
                const bool ok = !is_nodata(v, r.has_nodata, r.nodata, r.type) && (r.mask.empty() || r.mask[src]) &&
                                std::isfinite(e);
                r.valid[row * r.w + c] = ok;
                if (ok) lo = std::min(lo, e), hi = std::max(hi, e);
            }
        const std::lock_guard<std::mutex> lock(merge);  // min / max: the same in any order
        r.emin = std::min(r.emin, lo), r.emax = std::max(r.emax, hi);
    });
}

void classify_values(Raster& r) {
    if (r.raw_f.empty()) classify_values(r, r.raw_d);
    else classify_values(r, r.raw_f);
}

// r.emin / r.emax from scaled values to metres: x -> x * unit (unit in (0, 1], vertical_unit) is
// monotone and keeps finite values finite, so this is the range and the validity that scaling
// every value to metres first gives.
void range_to_metres(Raster& r) { r.emin *= r.unit, r.emax *= r.unit; }

// Band types whose every value a float holds exactly.
bool float_exact(GDALDataType t) {
    return t == GDT_Float32 || t == GDT_Byte || t == GDT_Int16 || t == GDT_UInt16;
}

// Size and geotransform (oriented: row 0 north, column 0 west) of the raster; no values yet.
Raster raster_header(GDALDataset& ds) {
    Raster r;
    r.w = ds.GetRasterXSize(), r.h = ds.GetRasterYSize();
    // No geotransform: pixel units as metres, row 0 on top (north).
    if (ds.GetGeoTransform(r.gt.data()) != CE_None) r.gt = {0.0, 1.0, 0.0, double(r.h), 0.0, -1.0};
    orient(r.gt, r.w, r.h, r.flip_c, r.flip_r);
    return r;
}

// The first band of `ds` into r's values, valid mask and range.
void read_values(GDALDataset& ds, Raster& r, const std::string& path) {
    if (ds.GetRasterCount() < 1) fail(path, "not a DEM raster (GDAL cannot read it)");
    GDALRasterBand& band = *ds.GetRasterBand(1);
    r.type = band.GetRasterDataType();
    if (float_exact(r.type)) read_band<float>(band, r, path);
    else read_band<double>(band, r, path);
    classify_values(r);
}

glm::dvec2 affine(const std::array<double, 6>& gt, int c, int r) {
    const double x = c + 0.5, y = r + 0.5;
    return {gt[0] + x * gt[1] + y * gt[2], gt[3] + x * gt[4] + y * gt[5]};
}

// Node centre (c, row) in the source CRS, scaled by `unit` (metres or degrees per CRS unit).
glm::dvec2 scaled_node(const Raster& r, double unit, double offset_x, int c, int row) {
    const glm::dvec2 p = affine(r.gt, c, row);
    return {p.x * unit + offset_x, p.y * unit};
}

[[noreturn]] void fail_utm(const std::string& path, int zone, bool north, const GeographicLib::GeographicErr& e) {
    fail(path, "DEM cannot be projected to UTM zone " + std::to_string(zone) + (north ? "N" : "S") + ": " + e.what());
}

// World (projected CRS) coordinates of the nodes, a row at a time: scaled_node with `unit`, or
// for a geographic DEM the nodes projected to UTM/UPS (utm_projection.hpp); lo / hi bound them.
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
        w.lonlat = [&r, unit, meridian](int c, int row) { return scaled_node(r, unit, meridian, c, row); };
        const glm::dvec2 centre = 0.5 * (w.lonlat(0, 0) + w.lonlat(r.w - 1, r.h - 1));
        int zone = options.utm_zone;
        bool north = options.north;
        try {
            if (zone <= 0) zone = GeographicLib::UTMUPS::StandardZone(centre.y, centre.x), north = centre.y >= 0.0;
            w.utm.emplace(r.w, r.h, w.lonlat, zone, north);  // the lattice form: a DEM is affine
            bound_nodes(r, w);  // projects every row's ends: a row out of the zone's range fails here
        } catch (const GeographicLib::GeographicErr& e) {
            fail_utm(path, zone, north, e);
        }
        t.utm_zone = zone, t.north = north;
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

void check_grid(const Raster& r, const std::string& path) {
    if (r.w < 2 || r.h < 2)
        fail(path, "DEM is too small (" + std::to_string(r.w) + "x" + std::to_string(r.h) +
                       " nodes; at least 2x2 needed)");
    if (r.emin > r.emax)  // the band pass widened the range at every valid node: none was
        fail(path, "DEM has no valid elevation (all nodata)");
}

// Elevation of node (c, row), metres (vertical unit `unit`): `emin`, the lowest valid one, at
// nodata nodes.
double node_elevation(const Raster& r, std::size_t row, int c, double unit, double emin) {
    return r.valid[row * r.w + c] ? (r.value(r.source(row, c)) * r.scale + r.offset) * unit : emin;
}

// f(node index, row, c, x, y) for every node, x, y its world coordinates relative to the bounds'
// rounded centre (t.origin) as floats; rows in parallel.
template <class F>
void each_node_xy(const Raster& r, const WorldXY& xy, const Terrain& t, const std::string& path, F&& f) {
    parallel_chunks(std::size_t(r.h), rows_per_chunk(r), [&](std::size_t r0, std::size_t r1) {
        std::vector<glm::dvec2> line(std::size_t(r.w));
        for (std::size_t row = r0; row < r1; ++row) {
            try {
                xy.row(r, int(row), line.data());
            } catch (const GeographicLib::GeographicErr& e) {
                fail_utm(path, t.utm_zone, t.north, e);
            }
            for (int c = 0; c < r.w; ++c) {
                const glm::dvec2 p = line[std::size_t(c)] - t.origin;
                f(row * r.w + c, row, c, float(p.x), float(p.y));
            }
        }
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

// A heights-only read's z: what fill_positions puts in pos[i].z (s: the vertical exaggeration)
// when the vertical unit is `unit` and the lowest valid elevation `emin` metres.
void fill_heights(const Raster& r, double unit, double emin, double s, std::vector<float>& z) {
    z.resize(std::size_t(r.w) * r.h);
    parallel_chunks(std::size_t(r.h), rows_per_chunk(r), [&](std::size_t r0, std::size_t r1) {
        for (std::size_t row = r0; row < r1; ++row)
            for (int c = 0; c < r.w; ++c) z[row * r.w + c] = float(node_elevation(r, row, c, unit, emin) * s);
    });
}

// A heights-only read of a geographic DEM: t.xy what fill_positions puts in pos[i].x, y (t.origin
// set).
void fill_xy(const Raster& r, const WorldXY& xy, Terrain& t, const std::string& path) {
    t.xy.resize(std::size_t(r.w) * r.h);
    each_node_xy(r, xy, t, path, [&](std::size_t i, std::size_t, int, float x, float y) { t.xy[i] = glm::vec2(x, y); });
}

// The values of `ds` read, classified and (heights not null) turned into heights as if the
// vertical unit were metres (most DEMs; read_dem redoes them otherwise): they need no spatial
// reference, which GDAL's GeoTIFF driver takes the unit from.
void read_heights(GDALDataset& ds, const std::string& path, double s, Raster& r, std::vector<float>* heights) {
    read_values(ds, r, path);
    if (heights && r.emin <= r.emax) fill_heights(r, 1.0, r.emin, s, *heights);  // emin: scaled = metres
}

// read_heights through a handle of its own opened by `driver` (a GDAL dataset serves one thread
// at a time), to run beside the spatial reference's build.
void read_heights(const std::string& path, const std::string& driver, double s, Raster& r, std::vector<float>* heights) {
    const QuietGdal quiet;  // GDAL's error handlers are per thread
    const char* const drivers[] = {driver.c_str(), nullptr};
    GDALDatasetUniquePtr ds = open_with(path, drivers);
    if (!ds) fail(path, "not a DEM raster (GDAL cannot read it)");
    read_heights(*ds, path, s, r, heights);
}

}  // namespace

Terrain read_dem(const std::string& path, const DemOptions& options) {
    const QuietGdal quiet;
    const double ve = options.vertical_exaggeration;
    if (!std::isfinite(ve) || ve <= 0.0) fail(path, "vertical exaggeration must be > 0");
    if (options.utm_zone < 0 || options.utm_zone > 60)
        fail(path, "UTM zone must be 1..60 (0 = standard zone), got " + std::to_string(options.utm_zone));
    GDALDatasetUniquePtr ds = open_raster(path);
    Raster r = raster_header(*ds);
    Terrain t;
    t.cols = r.w, t.rows = r.h;
    t.vertical_exaggeration = ve;
    t.source = path;
    t.geotransform = r.gt;
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
            if (heights && xy->utm) fill_xy(r, *xy, t, path);
        } catch (...) {
            crs_error = std::current_exception();
        }
    };
    if (driver == "GTiff") {
        run_beside([&] { read_heights(path, driver, ve, r, heights); }, crs);
    } else {
        read_heights(*ds, path, ve, r, heights);
        crs();
    }
    range_to_metres(r);
    check_grid(r, path);
    if (crs_error) std::rethrow_exception(crs_error);
    if (!xy->utm) t.xy_unit = xy->unit;  // an affine grid: affine_node_xy gives pos.xy
    t.elevation_min = r.emin, t.elevation_max = r.emax;
    if (!heights) fill_positions(r, *xy, t, path);
    else if (r.unit != 1.0) fill_heights(r, r.unit, r.emin, ve, t.z);  // not metres after all
    t.valid = std::move(r.valid);
    return t;
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
