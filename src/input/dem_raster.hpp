// A DEM's first band as GDAL reads it, for dem_reader.cpp (internal to src/input): the values in
// source order with their conversion to metres and, in our orientation (row 0 north, column 0
// west), the valid mask and the range of valid elevations; opening the file, reading and
// classifying the values, and the nodes' heights (metres times the vertical exaggeration).
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/big_allocator.hpp"

namespace penink::dem {

// The band as read: values in source order (float where that holds them exactly: the same
// doubles, half the memory) and their conversion to metres; in our orientation (row 0 north,
// column 0 west) the valid mask and the range of valid elevations (scaled values, metres once
// range_to_metres has run).
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
    // The first value in source order (a value that is not nodata) beyond max_elevation, inf
    // included: its source index (npos: none) and value.
    std::size_t out_of_range = npos;
    double out_of_range_value = 0.0;
    static constexpr std::size_t npos = std::size_t(-1);

    std::size_t source(std::size_t row, int c) const {
        return (flip_r ? std::size_t(h) - 1 - row : row) * std::size_t(w) + std::size_t(flip_c ? w - 1 - c : c);
    }
    double value(std::size_t src) const { return raw_f.empty() ? raw_d[src] : double(raw_f[src]); }
};

// Largest magnitude of a valid elevation (scaled value, the DEM's vertical unit): a value beyond
// (1e30, inf: a nodata marker the file does not declare) is an error, not a height. NaN is nodata.
constexpr double max_elevation = 1e6;

// Throws penink::Error (stage "input", file = path, ExitCode::bad_input).
[[noreturn]] void fail(const std::string& path, const std::string& what);

// Keeps GDAL quiet for the lifetime of the guard: our error line is the only message.
struct QuietGdal {
    QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); }
    ~QuietGdal() {
        CPLErrorReset();
        CPLPopErrorHandler();
    }
};

// Opens `path` as a raster (GTiff alone first, then every driver); fails "no such file" or "not a
// DEM raster (GDAL cannot read it)".
GDALDatasetUniquePtr open_raster(const std::string& path);

// A text grid (ESRI or GRASS ASCII) whose header declares more values than a file of
// `file_bytes` can hold (each value takes a digit and a separator): fails "ASCII grid declares
// WxH values but its N bytes hold at most M", before any value is read or allocated.
void check_text_grid_size(GDALDataset& ds, const std::string& path, std::uint64_t file_bytes);

// A cell size of zero, below zero in a text grid (ESRI or GRASS ASCII: cellsize, dx, dy) or not
// finite, or a geotransform whose cells have no area: fails "cell size must be > 0 (got S)" or
// "geotransform gives cells of no area (zero or non-finite cell size)".
void check_cell_size(GDALDataset& ds, const std::string& path);

// Size and geotransform (oriented: row 0 north, column 0 west) of the raster; no values yet.
Raster raster_header(GDALDataset& ds);

// Metres per vertical unit from the band's unit string (metres when unknown or empty).
double vertical_unit(GDALRasterBand& band);

// Rows per parallel chunk of a per-node loop: chunks of at least 64 K nodes.
std::size_t rows_per_chunk(const Raster& r);

// r.emin / r.emax from scaled values (what the read leaves) to metres: x -> x * unit (unit in
// (0, 1], vertical_unit) is monotone and keeps finite values finite, so this is the range and the
// validity that scaling every value to metres first gives.
inline void range_to_metres(Raster& r) { r.emin *= r.unit, r.emax *= r.unit; }

// Elevation of node (c, row), metres (vertical unit `unit`): `emin`, the lowest valid one, at
// nodata nodes.
inline double node_elevation(const Raster& r, std::size_t row, int c, double unit, double emin) {
    return r.valid[row * r.w + c] ? (r.value(r.source(row, c)) * r.scale + r.offset) * unit : emin;
}

// A heights-only read's z (s: the vertical exaggeration): what fill_positions puts in pos[i].z,
// with r's vertical unit and lowest valid elevation in metres (range_to_metres done). r's values
// are given back as their rows are converted (release_big_pages: the read holds about the
// heights, the flags and 8 MiB, not the values besides) and are gone after.
void take_heights(Raster& r, double s, std::vector<float>& z);

// Rows a read holds at a time: about 8 MiB of values of `value_bytes` each in a row of `width`, in
// whole rows of the band's blocks (each block decoded once when bands are read in turn), at least
// one row of blocks.
int band_rows(GDALRasterBand& band, int width, std::size_t value_bytes);

// The band's type, nodata value, scale and offset into r (what a read of its values needs besides
// them; read_heights sets them too).
void band_info(GDALRasterBand& band, Raster& r);

// Rows [y0, y1) of `band` in our orientation (row 0 north) into `rows`, a Raster of those rows
// alone (r's width, type, scale, offset, unit, nodata and flips, band_info's; h = y1 - y0): their
// values, mask, valid flags and range of scaled values as read_heights leaves a whole band's,
// out_of_range an index in the whole band's source order.
void read_rows(GDALRasterBand& band, const Raster& r, int y0, int y1, Raster& rows, const std::string& path);

// The values of `ds` read into r (values, valid mask, range of scaled values): none of it needs
// the spatial reference, which GDAL's GeoTIFF driver takes the unit from.
void read_heights(GDALDataset& ds, const std::string& path, Raster& r);

// read_heights through a handle of its own opened by `driver` (a GDAL dataset serves one thread
// at a time), to run beside the spatial reference's build.
void read_heights(const std::string& path, const std::string& driver, Raster& r);

}  // namespace penink::dem
