// GeoTIFF rasters of the drainage grid for inspection in a GIS (written with GDAL), georeferenced
// like the source DEM (its CRS; its geotransform scaled by the resample factor so pixel centres
// are the drainage points): flow_direction.tif (Byte, ESRI D8 codes 1=E 2=SE 4=S 8=SW 16=W 32=NW
// 64=N 128=NE, 0 = outlet draining off the grid, nodata 255), accumulation.tif (UInt32, points
// draining through the cell including itself, nodata 0), basin.tif (UInt32 label, nodata 0),
// stream_order.tif (Byte Strahler order, nodata 0).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "drainage/drainage_build.hpp"

namespace penink {

struct DrainageGeoref {
    std::array<double, 6> gt{0.0, 1.0, 0.0, 0.0, 0.0, -1.0};  // GDAL geotransform of the grid
    std::string wkt;                                          // CRS of the source DEM
};

// The DEM's geotransform and CRS (GDAL), turned into the drainage grid's: fine pixel (i, j) is
// centred on drainage point (i, j). Accounts for the Terrain's crop offset and for read_dem's
// north-up / west-left flips. Throws penink::Error("drainage", dem_path, ...) if GDAL cannot open it.
DrainageGeoref drainage_georef(const std::string& dem_path, const Terrain& t, int factor);

// The four rasters' file names, in the order write_drainage_raster numbers them.
std::vector<std::string> drainage_raster_names();

// Whether `path` is a raster penink drainage wrote (its GeoTIFF metadata item
// PENINK_DRAINAGE_RASTER); --rasters replaces no other file.
bool is_drainage_raster(const std::string& path);

// Writes raster `which` (drainage_raster_names order) as a GeoTIFF at `path` (a temporary the
// caller places). Throws penink::Error("drainage", shown, "cannot write raster (GDAL's reason)")
// on any GDAL error, the disk full included.
void write_drainage_raster(std::size_t which, const std::string& path, const std::string& shown,
                           const DrainageGeoref& geo, int cols, int rows, const std::vector<std::uint8_t>& valid,
                           const DrainageResult& res);

// A GeoTIFF of heights (Float32, metres, nodata NaN, georeferenced like the DEM at factor 1: the
// filled DEM of `penink fill`) written a band of rows at a time in row order, so that a grid of
// any size passes through in bounded memory: strips of height_raster_strip_rows rows, DEFLATE
// at level 1 with the floating-point predictor, compressed on all cores, BigTIFF where the file
// may pass 4 GiB. (Level 6, the default, took 42 % of `penink fill`'s CPU on jacksboro x29 for a
// file 10 % smaller: 26.2 MB against 29.2.) Errors: Error("drainage", shown, "cannot write raster (GDAL's reason)"), the disk full
// included (found at the latest by close()); `stage` names the command's stage instead.
inline constexpr int height_raster_strip_rows = 16;
class HeightRasterWriter {
public:
    HeightRasterWriter(const std::string& path, const std::string& shown, const DrainageGeoref& geo, int cols, int rows,
                       const std::string& stage = "drainage");
    ~HeightRasterWriter();
    // Rows [y0, y1) (row-major, cols a row): z where valid, NaN elsewhere. y0 a multiple of the
    // strip rows, or the rows before it all written.
    void write_rows(int y0, int y1, const float* z, const std::uint8_t* valid);
    // Flushes and closes the file.
    void close();

private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace penink
