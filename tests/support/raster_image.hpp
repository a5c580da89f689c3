// Shared by the tests that compare rasterised output (tests/export, tests/cli): a PNG read with
// OpenImageIO as RGB composited over white (OIIO hands back associated alpha), and the difference
// measure their tolerances are stated in.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace penink::test {

struct RasterImage {
    int w = 0, h = 0;
    std::vector<float> rgb;  // 0..255, alpha composited over white
};

inline RasterImage read_rgb_over_white(const std::string& path) {
    RasterImage im;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return im;
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> px(std::size_t(spec.width) * spec.height * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data());
    im.w = spec.width, im.h = spec.height;
    for (std::size_t i = 0; i < std::size_t(im.w) * im.h; ++i) {
        const float* p = &px[i * spec.nchannels];
        const float a = spec.nchannels == 4 ? p[3] : 1.0f;
        for (int c = 0; c < 3; ++c) im.rgb.push_back(255.0f * (p[spec.nchannels >= 3 ? c : 0] + (1.0f - a)));
    }
    return im;
}

struct RasterDiff {
    double mean = 1.0, within = 0.0;  // mean |diff| / 255, share of pixels within 64 levels
};

// Worst case (mean 1, within 0) when the sizes differ or an image is empty.
inline RasterDiff raster_diff(const RasterImage& a, const RasterImage& b) {
    RasterDiff d;
    if (a.w != b.w || a.h != b.h || a.rgb.empty()) return d;
    double sum = 0.0;
    std::size_t within = 0, n = std::size_t(a.w) * a.h;
    for (std::size_t i = 0; i < n; ++i) {
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float e = std::fabs(a.rgb[3 * i + c] - b.rgb[3 * i + c]);
            sum += e, worst = std::max(worst, e);
        }
        within += worst <= 64.0f;
    }
    d.mean = sum / (3.0 * n) / 255.0, d.within = double(within) / n;
    return d;
}

inline bool have_tool(const char* tool) {
    return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

}  // namespace penink::test
