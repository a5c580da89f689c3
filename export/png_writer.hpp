// PNG writer: rasterises the StyledDrawing (rasterise.hpp) and writes 8-bit RGB (encoded by
// png_encode.hpp, zlib loaded on first use; no OpenImageIO in the penink binary). Resolution: one image pixel = dpi/96 PNG pixels without a page; with a page,
// the whole page at `dpi` (page size in mm * dpi / 25.4), the drawing placed as in SVG/PDF.
#pragma once
#include <string>

#include "export/page.hpp"
#include "export/rasterise.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// The output size and image->PNG transform for these page options.
RasterTransform png_transform(const StyledDrawing& drawing, const PageOptions& page,
                              const std::string& path = "");

// Rasterises and writes atomically; errors Error("export", path, "cannot write file (...)").
void write_png(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

}  // namespace penink
