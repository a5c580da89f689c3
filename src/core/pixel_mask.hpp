// Raster inputs of the lines stage as read back from the GPU passes: a binary pixel mask and a
// per-pixel eye-distance image, both width x height, row 0 = top image row (origin top-left,
// y down, pixel (x, y) covers [x, x+1] x [y, y+1] in image pixels), depth in metres/world units.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace penink {

struct PixelMask {
    int width = 0, height = 0;
    std::vector<std::uint8_t> on;  // on[y*width + x] != 0: pixel set
};

struct DepthImage {
    int width = 0, height = 0;
    std::vector<float> depth;  // eye distance per pixel, +inf (any non-finite value) where empty
};

// Throws penink::Error("lines", "", "<what>: size WxH does not match N values") when the vector
// size disagrees with width*height or a dimension is negative.
void check_mask(const PixelMask& mask, const std::string& what);
void check_depth(const DepthImage& depth, const std::string& what);

// True when the image holds no pixels (width or height 0): "no depth available".
inline bool is_empty(const DepthImage& d) { return d.width <= 0 || d.height <= 0; }

// Depth at pixel (x, y); when it is empty (non-finite) the nearest valid pixel of its 3x3
// neighbourhood: edge neighbours before corner neighbours, the smallest depth among equals
// (the occluding surface). Returns +inf when nothing valid is near or (x, y) is outside.
float sample_depth(const DepthImage& d, int x, int y);

// Depth at an image point on the pixel grid (e.g. a pixel corner): the smallest valid depth of
// the up to 4 pixels touching the point, else sample_depth of the pixel containing it.
float sample_depth_at_point(const DepthImage& d, glm::vec2 p);

}  // namespace penink
