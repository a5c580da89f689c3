// Anti-aliased rasteriser for a StyledDrawing (the PNG writer's engine): strokes as unions of
// capsules (round caps and joins) with box-filter coverage from the distance to each segment,
// surface rings by even-odd scanline fill with 4 sub-scanlines and exact horizontal coverage,
// composited source-over in layer order onto the background, in 8-bit sRGB values like SVG
// renderers. Output pixel = (image pixel * scale + offset), y down.
#pragma once
#include <cstdint>
#include <vector>

#include "export/styled_drawing.hpp"

namespace penink {

struct RasterTransform {
    int width = 0, height = 0;  // output pixels
    double scale = 1.0;         // output pixels per image pixel
    double offset_x = 0.0, offset_y = 0.0;
};

struct RgbImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel, top row first
};

RgbImage rasterise(const StyledDrawing& drawing, const RasterTransform& transform);

}  // namespace penink
