#include "render/readback.hpp"

#include <algorithm>
#include <limits>

namespace penink {

namespace {
template <typename T>
void flip_rows(std::vector<T>& v, int width, int height) {
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(v.begin() + std::ptrdiff_t(y) * width, v.begin() + std::ptrdiff_t(y + 1) * width,
                         v.begin() + std::ptrdiff_t(height - 1 - y) * width);
}
}  // namespace

DepthImage read_depth_image(const GlApi& gl, GLuint texture, int width, int height) {
    DepthImage img;
    img.width = width, img.height = height;
    img.depth.resize(std::size_t(width) * height);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.GetTextureImage(texture, 0, GL_RED, GL_FLOAT, GLsizei(img.depth.size() * sizeof(float)),
                       img.depth.data());
    flip_rows(img.depth, width, height);
    for (float& d : img.depth)
        if (d >= 1.0e29f) d = std::numeric_limits<float>::infinity();
    return img;
}

PixelMask read_pixel_mask(const GlApi& gl, GLuint texture, int width, int height) {
    PixelMask mask;
    mask.width = width, mask.height = height;
    mask.on.resize(std::size_t(width) * height);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.GetTextureImage(texture, 0, GL_RED, GL_UNSIGNED_BYTE, GLsizei(mask.on.size()), mask.on.data());
    flip_rows(mask.on, width, height);
    return mask;
}

}  // namespace penink
