// Raster output (.png .tif .tiff .jpg .jpeg .webp .exr): rasterises the StyledDrawing
// (rasterise.hpp) and encodes it with OpenImageIO, by extension, with the resolution (dpi) and
// text metadata (Software, ImageDescription). OpenImageIO lives in the module penink_oiio.so
// (raster_module.hpp), dlopen()ed on the first raster only: a process that writes only vector
// files does not load it. Resolution: one image pixel = dpi/96 output pixels without a page;
// with a page, the whole page at `dpi` (page size in mm * dpi / 25.4), the drawing placed as in
// SVG/PDF.
#pragma once
#include <string>
#include <vector>

#include "export/page.hpp"
#include "export/rasterise.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// Most pixels a raster output may have (3 bytes each while it is drawn).
constexpr double max_raster_pixels = 1.0e9;

// The raster extensions, lower case with the dot: .png .tif .tiff .jpg .jpeg .webp .exr.
const std::vector<std::string>& raster_extensions();
// Whether `ext` (lower case, with the dot) is one of them.
bool is_raster_extension(const std::string& ext);

// A path's extension, lower case, with its dot (".png"); "" when it has none.
std::string lower_extension(const std::string& path);

// The output size and image->raster transform for these page options, for a drawing of width x
// height image pixels. Throws Error("export", path, "PNG of WxH pixels is too large (lower
// --dpi)") (the format named by path's extension) beyond max_raster_pixels, and page_layout's
// errors.
RasterTransform raster_transform(int width, int height, const PageOptions& page, const std::string& path = "");
RasterTransform raster_transform(const StyledDrawing& drawing, const PageOptions& page, const std::string& path = "");

// The raster writer module is looked for beside the running executable, then in ../lib/penink/
// from it. check_raster_writer only finds it (cheap: what check_output_targets asks before
// drawing); load_raster_writer loads it if it is not loaded yet (OpenImageIO's start-up, once per
// process). Both throw Error("export", path, "cannot write raster images: ...") naming where it
// was looked for, or the loader's reason.
void check_raster_writer(const std::string& path);
void load_raster_writer(const std::string& path);

// The raster file's bytes in the format named by path's extension (loads the module).
// Errors: load_raster_writer's, Error("export", path, "cannot write file (<OpenImageIO's reason>)").
std::string raster_document(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

// Rasterises and writes atomically.
void write_raster(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

}  // namespace penink
