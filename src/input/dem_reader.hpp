// Reads a DEM raster with GDAL (GeoTIFF, ESRI ASCII grid, anything GDAL reads) into a Terrain:
// nodata nodes marked invalid; a DEM in geographic coordinates (degrees) projected node by node
// to the standard UTM zone of its centre with GeographicLib (or `utm_zone` when > 0).
// Node = cell centre (GDAL pixel-is-area: centre of cell (c, r) is GT(c+0.5, r+0.5)).
#pragma once
#include <string>

#include "input/terrain.hpp"

namespace penink {

struct DemOptions {
    double vertical_exaggeration = 1.0;
    int utm_zone = 0;      // force this UTM zone for geographic DEMs (0 = standard zone of centre)
    bool north = true;     // hemisphere for a forced zone
};

// Throws penink::Error (stage "input", file = path) with one clear line for: missing file,
// unreadable or non-raster file, no CRS-less geotransform problems that make no grid, all-nodata
// DEM, a DEM smaller than 2x2 nodes, non-positive exaggeration.
Terrain read_dem(const std::string& path, const DemOptions& options = {});

}  // namespace penink
