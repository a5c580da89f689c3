// Small DEM files for tests (input and drainage): writers for ESRI ASCII grids (rows north
// first, lower-left corner and cell size in CRS units) and Float32 GeoTIFFs (GDAL) with a given
// geotransform, CRS (EPSG code, 0 = none) and nodata, plus the per-test temporary folder
// (support/temp_dir.hpp) they are usually written into.
#pragma once
#include <array>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "support/temp_dir.hpp"

namespace penink::test {

inline std::string write_text(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
    return path;
}

// ESRI ASCII grid; rows are given north first, as in the file.
inline std::string write_asc(const std::string& path, int cols, const std::vector<std::vector<double>>& rows,
                             double xll, double yll, double cell, const std::string& nodata_line = "") {
    std::ofstream f(path);
    f << "ncols " << cols << "\nnrows " << rows.size() << "\nxllcorner " << xll << "\nyllcorner " << yll
      << "\ncellsize " << cell << "\n" << nodata_line;
    for (const auto& row : rows) {
        for (double v : row) f << v << " ";
        f << "\n";
    }
    return path;
}

// Float32 GeoTIFF; values row-major in file order (row 0 = first row of the file).
inline std::string write_tif(const std::string& path, int cols, int rows, const std::vector<float>& values,
                             const std::array<double, 6>& gt, int epsg = 0, const double* nodata = nullptr) {
    GDALAllRegister();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDatasetUniquePtr ds(drv->Create(path.c_str(), cols, rows, 1, GDT_Float32, nullptr));
    std::array<double, 6> g = gt;
    ds->SetGeoTransform(g.data());
    if (epsg) {
        OGRSpatialReference srs;
        srs.importFromEPSG(epsg);
        ds->SetSpatialRef(&srs);
    }
    GDALRasterBand* band = ds->GetRasterBand(1);
    if (nodata) band->SetNoDataValue(*nodata);
    std::vector<float> v = values;
    if (band->RasterIO(GF_Write, 0, 0, cols, rows, v.data(), cols, rows, GDT_Float32, 0, 0) != CE_None)
        ADD_FAILURE() << "cannot write " << path;
    return path;
}

}  // namespace penink::test
