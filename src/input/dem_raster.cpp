#include "input/dem_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include <cpl_vsi.h>
#include <gdal_frmts.h>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/parallel_chunks.hpp"

namespace penink::dem {

void fail(const std::string& path, const std::string& what) { throw Error("input", path, what, ExitCode::bad_input); }

namespace {

GDALDatasetUniquePtr open_with(const std::string& path, const char* const* drivers) {
    return GDALDatasetUniquePtr(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr)));
}

bool is_nodata(double v, bool has_nodata, double nodata, GDALDataType type) {
    if (std::isnan(v)) return true;
    if (!has_nodata) return false;
    if (type == GDT_Float32) return float(v) == float(nodata);
    return v == nodata;
}

// The per-dataset or alpha mask of the band's source rows [y, y + n) (source order), empty when
// it has none beyond the nodata value.
std::vector<std::uint8_t> read_mask(GDALRasterBand& band, const std::string& path, int y, int n) {
    const int flags = band.GetMaskFlags();
    if (flags & (GMF_ALL_VALID | GMF_NODATA)) return {};
    std::vector<std::uint8_t> mask(std::size_t(band.GetXSize()) * std::size_t(n));
    if (band.GetMaskBand()->RasterIO(GF_Read, 0, y, band.GetXSize(), n, mask.data(), band.GetXSize(), n, GDT_Byte, 0,
                                     0) != CE_None)
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

// Reads the band as T into r.raw_f / r.raw_d, with its mask (band_info first).
template <class T>
void read_band(GDALRasterBand& band, Raster& r, const std::string& path) {
    auto& raw = [&]() -> auto& {
        if constexpr (sizeof(T) == 4) return r.raw_f;
        else return r.raw_d;
    }();
    raw.resize(std::size_t(r.w) * r.h);
    const GDALDataType as = sizeof(T) == 4 ? GDT_Float32 : GDT_Float64;
    // A band of rows at a time, the blocks GDAL caches for it dropped after it: the read holds the
    // values and about a band of blocks, not a second copy of the raster in GDAL's cache.
    const int rows = band_rows(band, r.w, sizeof(T));
    for (int y = 0; y < r.h; y += rows) {
        const int n = std::min(rows, r.h - y);
        if (band.RasterIO(GF_Read, 0, y, r.w, n, raw.data() + std::size_t(y) * std::size_t(r.w), r.w, n, as, 0, 0) != CE_None)
            fail(path, "not a DEM raster (GDAL cannot read it)");
        band.FlushCache();
    }
    r.mask = read_mask(band, path, 0, r.h);
    if (GDALRasterBand* m = band.GetMaskBand(); m && !r.mask.empty()) m->FlushCache();
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
        std::size_t bad = Raster::npos;
        double bad_value = 0.0;
        for (std::size_t row = r0; row < r1; ++row)
            for (int c = 0; c < r.w; ++c) {
                const std::size_t src = r.source(row, c);
                const double v = double(raw[src]), e = v * r.scale + r.offset;
                bool ok = !is_nodata(v, r.has_nodata, r.nodata, r.type) && (r.mask.empty() || r.mask[src]) &&
                          !std::isnan(e);
                if (ok && !(std::abs(e) <= max_elevation)) {
                    if (src < bad) bad = src, bad_value = e;
                    ok = false;
                }
                r.valid[row * r.w + c] = ok;
                if (ok) lo = std::min(lo, e), hi = std::max(hi, e);
            }
        const std::lock_guard<std::mutex> lock(merge);  // min / max: the same in any order
        r.emin = std::min(r.emin, lo), r.emax = std::max(r.emax, hi);
        if (bad < r.out_of_range) r.out_of_range = bad, r.out_of_range_value = bad_value;
    });
}

void classify_values(Raster& r) {
    if (r.raw_f.empty()) classify_values(r, r.raw_d);
    else classify_values(r, r.raw_f);
}

// Band types whose every value a float holds exactly.
bool float_exact(GDALDataType t) {
    return t == GDT_Float32 || t == GDT_Byte || t == GDT_Int16 || t == GDT_UInt16;
}

// The first band of `ds` into r's values, valid mask and range.
void read_values(GDALDataset& ds, Raster& r, const std::string& path) {
    if (ds.GetRasterCount() < 1) fail(path, "not a DEM raster (GDAL cannot read it)");
    GDALRasterBand& band = *ds.GetRasterBand(1);
    band_info(band, r);
    if (float_exact(r.type)) read_band<float>(band, r, path);
    else read_band<double>(band, r, path);
    classify_values(r);
}

}  // namespace

namespace {

// GDAL's drivers less those that read what a file names (other files, URLs, services): VRT,
// the web services and the catalogues. A DEM is one local file, whatever its content says.
struct LocalDrivers {
    std::vector<std::string> names;
    std::vector<const char*> list;
    LocalDrivers() {
        GDALAllRegister();
        // vsicurl refuses every file when no extension is allowed: no request leaves the machine
        // even through a driver this list does not know.
        CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_EXTENSIONS", ".penink-reads-local-files-only");
        CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", "0");
        const char* const refused[] = {"VRT", "WMS", "WMTS", "WCS", "HTTP", "DAAS", "EEDA", "EEDAI", "PLMosaic",
                                       "OGCAPI", "STACIT", "STACTA", "GTI", "NGW", "DERIVED", "PLScenes",
                                       "PostGISRaster", "MEM", "GNMFile", "GNMDatabase"};
        for (int i = 0; i < GDALGetDriverCount(); ++i) {
            const char* name = GDALGetDescription(GDALGetDriver(i));
            bool ok = true;
            for (const char* r : refused) ok = ok && !EQUAL(name, r);
            if (ok) names.push_back(name);
        }
        for (const std::string& n : names) list.push_back(n.c_str());
        list.push_back(nullptr);
    }
};

}  // namespace

GDALDatasetUniquePtr open_raster(const std::string& path) {
    check_input_file("input", path);  // local, a regular file: no FIFO, device, URL or /vs path
    VSIStatBufL st;
    if (VSIStatExL(path.c_str(), &st, VSI_STAT_EXISTS_FLAG) != 0) fail(path, "no such file");
    GDALRegister_GTiff();
    const char* const gtiff[] = {"GTiff", nullptr};
    GDALDatasetUniquePtr ds = open_with(path, gtiff);
    if (!ds) {
        static const LocalDrivers local;
        ds = open_with(path, local.list.data());
    }
    if (GDALDriverH vrt = GDALGetDriverByName("VRT"); !ds && vrt && GDALIdentifyDriver(path.c_str(), nullptr) == vrt)
        fail(path, "a VRT is refused (it can name other files and network sources; gdal_translate it to a GeoTIFF)");
    if (!ds || ds->GetRasterCount() < 1 || ds->GetRasterXSize() < 1 || ds->GetRasterYSize() < 1)
        fail(path, "not a DEM raster (GDAL cannot read it)");
    check_text_grid_size(*ds, path, std::uint64_t(st.st_size));
    check_cell_size(*ds, path);
    return ds;
}

void check_cell_size(GDALDataset& ds, const std::string& path) {
    std::array<double, 6> gt{};
    if (ds.GetGeoTransform(gt.data()) != CE_None) return;  // none: pixel units
    const std::string driver = ds.GetDriver() ? ds.GetDriver()->GetDescription() : "";
    char text[64];
    if (driver == "AAIGrid" || driver == "GRASSASCIIGrid") {  // cellsize (or dx, dy) as written: > 0
        const double size = !(gt[1] > 0.0) ? gt[1] : -gt[5];
        std::snprintf(text, sizeof text, "%g", size);
        if (!(gt[1] > 0.0 && -gt[5] > 0.0) || !std::isfinite(gt[1]) || !std::isfinite(gt[5]))
            fail(path, std::string("cell size must be > 0 (got ") + text + ")");
    }
    const double area = gt[1] * gt[5] - gt[2] * gt[4];
    bool finite = std::isfinite(area);
    for (double g : gt) finite = finite && std::isfinite(g);
    if (!finite || area == 0.0) fail(path, "geotransform gives cells of no area (zero or non-finite cell size)");
}

void check_text_grid_size(GDALDataset& ds, const std::string& path, std::uint64_t file_bytes) {
    const std::string driver = ds.GetDriver() ? ds.GetDriver()->GetDescription() : "";
    if (driver != "AAIGrid" && driver != "GRASSASCIIGrid") return;
    const double values = double(ds.GetRasterXSize()) * double(ds.GetRasterYSize());
    const double most = std::floor((double(file_bytes) + 1.0) / 2.0);  // a digit and a separator each
    if (values > most)
        fail(path, "ASCII grid declares " + std::to_string(ds.GetRasterXSize()) + "x" +
                       std::to_string(ds.GetRasterYSize()) + " values but its " + std::to_string(file_bytes) +
                       " bytes hold at most " + std::to_string(std::uint64_t(most)));
}

double vertical_unit(GDALRasterBand& band) {
    const std::string u = band.GetUnitType();
    if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
    if (u == "US survey foot" || u == "ftUS" || u == "us-ft") return 1200.0 / 3937.0;
    return 1.0;
}

std::size_t rows_per_chunk(const Raster& r) { return std::max<std::size_t>(1, 65536 / std::size_t(r.w)); }

Raster raster_header(GDALDataset& ds) {
    Raster r;
    r.w = ds.GetRasterXSize(), r.h = ds.GetRasterYSize();
    // No geotransform: pixel units as metres, row 0 on top (north).
    if (ds.GetGeoTransform(r.gt.data()) != CE_None) r.gt = {0.0, 1.0, 0.0, double(r.h), 0.0, -1.0};
    orient(r.gt, r.w, r.h, r.flip_c, r.flip_r);
    return r;
}

void take_heights(Raster& r, double s, std::vector<float>& z) {
    const std::size_t w = std::size_t(r.w), h = std::size_t(r.h);
    z.clear();
    z.reserve(w * h);
    // Bands of rows converted on every core into `band`, appended to z (whose pages are touched
    // as it grows), the values' rows behind them given back.
    const std::size_t band_rows = std::max<std::size_t>(1, (std::size_t(2) << 20) / w);  // 8 MiB of floats
    std::vector<float> band;
    void* raw = r.raw_f.empty() ? static_cast<void*>(r.raw_d.data()) : static_cast<void*>(r.raw_f.data());
    const std::size_t value_bytes = r.raw_f.empty() ? sizeof(double) : sizeof(float);
    const std::size_t raw_bytes = (r.raw_f.empty() ? r.raw_d.size() : r.raw_f.size()) * value_bytes;
    for (std::size_t b0 = 0; b0 < h; b0 += band_rows) {
        const std::size_t b1 = std::min(h, b0 + band_rows);
        band.resize((b1 - b0) * w);
        parallel_chunks(b1 - b0, rows_per_chunk(r), [&](std::size_t r0, std::size_t r1) {
            for (std::size_t i = r0; i < r1; ++i)
                for (int c = 0; c < r.w; ++c) band[i * w + std::size_t(c)] = float(node_elevation(r, b0 + i, c, r.unit, r.emin) * s);
        });
        z.insert(z.end(), band.begin(), band.end());
        if (!r.flip_r) release_big_pages(raw, raw_bytes, 0, b1 * w * value_bytes);  // source rows 0 .. b1 - 1
    }
    r.raw_f = {}, r.raw_d = {};
}

void read_heights(GDALDataset& ds, const std::string& path, Raster& r) { read_values(ds, r, path); }

int band_rows(GDALRasterBand& band, int width, std::size_t value_bytes) {
    int block_w = 0, block_h = 0;
    band.GetBlockSize(&block_w, &block_h);
    const std::int64_t block = std::max(block_h, 1);
    const std::int64_t per = (std::int64_t(8) << 20) / (std::max<std::int64_t>(width, 1) * std::int64_t(value_bytes) * block);
    return int(std::min<std::int64_t>(block * std::max<std::int64_t>(per, 1), std::numeric_limits<int>::max()));
}

void band_info(GDALRasterBand& band, Raster& r) {
    r.type = band.GetRasterDataType();
    int has = 0, has_scale = 0, has_offset = 0;
    r.nodata = band.GetNoDataValue(&has), r.has_nodata = has != 0;
    const double scale = band.GetScale(&has_scale), offset = band.GetOffset(&has_offset);
    r.scale = has_scale ? scale : 1.0, r.offset = has_offset ? offset : 0.0;
}

void read_rows(GDALRasterBand& band, const Raster& r, int y0, int y1, Raster& rows, const std::string& path) {
    rows.w = r.w, rows.h = y1 - y0;
    rows.type = r.type, rows.scale = r.scale, rows.offset = r.offset, rows.unit = r.unit;
    rows.has_nodata = r.has_nodata, rows.nodata = r.nodata, rows.flip_c = r.flip_c, rows.flip_r = r.flip_r;
    rows.emin = std::numeric_limits<double>::max(), rows.emax = -rows.emin;
    rows.out_of_range = Raster::npos;
    const int sy = r.flip_r ? r.h - y1 : y0;  // the rows' first in source order
    const std::size_t n = std::size_t(rows.w) * std::size_t(rows.h);
    auto read = [&](auto& raw, GDALDataType as) {
        raw.resize(n);
        if (band.RasterIO(GF_Read, 0, sy, rows.w, rows.h, raw.data(), rows.w, rows.h, as, 0, 0) != CE_None)
            fail(path, "not a DEM raster (GDAL cannot read it)");
    };
    if (float_exact(r.type)) rows.raw_d = {}, read(rows.raw_f, GDT_Float32);
    else rows.raw_f = {}, read(rows.raw_d, GDT_Float64);
    rows.mask = read_mask(band, path, sy, rows.h);
    classify_values(rows);
    if (rows.out_of_range != Raster::npos) rows.out_of_range += std::size_t(sy) * std::size_t(rows.w);
}

void read_heights(const std::string& path, const std::string& driver, Raster& r) {
    const QuietGdal quiet;  // GDAL's error handlers are per thread
    const char* const drivers[] = {driver.c_str(), nullptr};
    GDALDatasetUniquePtr ds = open_with(path, drivers);
    if (!ds) fail(path, "not a DEM raster (GDAL cannot read it)");
    read_heights(*ds, path, r);
}

}  // namespace penink::dem
