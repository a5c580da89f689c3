// A georeferenced raster's side files: the world file (six lines A, D, B, E, C, F: the affine
// from raster pixel centres to map coordinates, X = A*col + B*row + C, Y = D*col + E*row + F with
// (C, F) the centre of pixel (0, 0); ESRI's world file convention, as GDALReadWorldFile reads it)
// and the CRS as GDAL's .aux.xml (a PAMDataset with the SRS), named PATH.aux.xml. The raster's
// pixels are not the drawing's: with --dpi or a page they are scaled and offset (raster_transform),
// and the transform here follows them.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/georeference.hpp"
#include "export/page.hpp"
#include "export/rasterise.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// Raster pixel corner coordinates -> map (GDAL order), for drawing pixels placed by `t`.
std::array<double, 6> raster_geotransform(const std::array<double, 6>& drawing_gt, const RasterTransform& t);

// The world file's name beside a raster, one per raster (a world file belongs to one raster):
// the extension's first and last letters and "w" (.pgw for .png, .tfw for .tif, .jgw for .jpg,
// .wpw for .webp, .erw for .exr; GDAL's first choice), and for .tiff and .jpeg, whose short form
// is .tif's and .jpg's, the extension and "w" (.tiffw, .jpegw; GDAL's second choice).
std::string world_file_path(const std::string& raster_path);

// For a .tiff or .jpeg raster, the short-form world file (.tfw, .jgw) that GDAL would read before
// the raster's own (world_file_path); "" for other rasters. check_output_targets refuses such a
// raster when that file exists and is not written by the same command.
std::string shadowing_world_file(const std::string& raster_path);

// The six lines (A, D, B, E, C, F) of a corner-based geotransform `gt`, exact decimals.
std::string world_file_text(const std::array<double, 6>& gt);

// GDAL's .aux.xml holding the CRS (WKT).
std::string aux_xml_text(const std::string& crs_wkt);

struct SideFile {
    std::string path;
    std::string bytes;
};

// The names of the side files a raster output `path` can have (world file, .aux.xml); none for a
// vector output. Those that a render does not write are stale (they describe an earlier raster)
// and export_drawings removes them once its outputs are in place.
std::vector<std::string> raster_side_file_names(const std::string& path);

// The side files of raster output `path`: the world file, and the .aux.xml when there is a CRS;
// none when the drawing is not georeferenced or `path` is not a raster. Throws raster_transform's
// errors.
std::vector<SideFile> raster_side_files(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

}  // namespace penink
