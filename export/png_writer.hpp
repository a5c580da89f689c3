// PNG writer: rasterises the StyledDrawing (rasterise.hpp) and writes 8-bit RGB (encoded by
// png_encode.hpp, zlib loaded on first use; no OpenImageIO in the penink binary). Resolution: one image pixel = dpi/96 PNG pixels without a page; with a page,
// the whole page at `dpi` (page size in mm * dpi / 25.4), the drawing placed as in SVG/PDF.
#pragma once
#include <string>

#include "export/page.hpp"
#include "export/rasterise.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// Most pixels a PNG may have (3 bytes each while it is drawn).
constexpr double max_png_pixels = 1.0e9;

// The output size and image->PNG transform for these page options, for a drawing of width x
// height image pixels. Throws Error("export", path, "PNG of WxH pixels is too large (lower
// --dpi)") beyond max_png_pixels, and page_layout's errors.
RasterTransform png_transform(int width, int height, const PageOptions& page, const std::string& path = "");
RasterTransform png_transform(const StyledDrawing& drawing, const PageOptions& page,
                              const std::string& path = "");

// The PNG file's bytes.
std::string png_document(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

// Rasterises and writes atomically; errors Error("export", path, "cannot write file (...)").
void write_png(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

}  // namespace penink
