// Reads GPU textures back into the lines stage's images, flipping rows so that row 0 is the top
// of the image (GL's row 0 is the bottom): R32F eye distances -> DepthImage (+inf where the
// pass wrote PENINK_FAR), R8 masks -> PixelMask.
#pragma once
#include "core/pixel_mask.hpp"
#include "render/gl_api.hpp"

namespace penink {

DepthImage read_depth_image(const GlApi& gl, GLuint texture, int width, int height);
PixelMask read_pixel_mask(const GlApi& gl, GLuint texture, int width, int height);

}  // namespace penink
