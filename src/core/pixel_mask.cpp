#include "core/pixel_mask.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace penink {

namespace {

void check_size(int w, int h, std::size_t n, const std::string& what) {
    if (w < 0 || h < 0 || static_cast<std::size_t>(w) * static_cast<std::size_t>(h) != n)
        throw Error("lines", "",
                    what + ": size " + std::to_string(w) + "x" + std::to_string(h) +
                        " does not match " + std::to_string(n) + " values",
                    ExitCode::internal);
}

float valid_at(const DepthImage& d, int x, int y) {
    if (x < 0 || y < 0 || x >= d.width || y >= d.height)
        return std::numeric_limits<float>::infinity();
    float v = d.depth[static_cast<std::size_t>(y) * d.width + x];
    return std::isfinite(v) ? v : std::numeric_limits<float>::infinity();
}

}  // namespace

void check_mask(const PixelMask& mask, const std::string& what) {
    check_size(mask.width, mask.height, mask.on.size(), what);
}

void check_depth(const DepthImage& depth, const std::string& what) {
    check_size(depth.width, depth.height, depth.depth.size(), what);
}

float sample_depth(const DepthImage& d, int x, int y) {
    float v = valid_at(d, x, y);
    if (std::isfinite(v)) return v;
    static constexpr int edge[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    static constexpr int corner[4][2] = {{1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
    for (const auto& ring : {edge, corner}) {
        float best = std::numeric_limits<float>::infinity();
        for (int i = 0; i < 4; ++i) best = std::fmin(best, valid_at(d, x + ring[i][0], y + ring[i][1]));
        if (std::isfinite(best)) return best;
    }
    return std::numeric_limits<float>::infinity();
}

float sample_depth_at_point(const DepthImage& d, glm::vec2 p) {
    int cx = static_cast<int>(std::lround(p.x)), cy = static_cast<int>(std::lround(p.y));
    if (std::fabs(p.x - cx) < 1e-4f && std::fabs(p.y - cy) < 1e-4f) {
        float best = std::fmin(std::fmin(valid_at(d, cx - 1, cy - 1), valid_at(d, cx, cy - 1)),
                               std::fmin(valid_at(d, cx - 1, cy), valid_at(d, cx, cy)));
        if (std::isfinite(best)) return best;
    }
    return sample_depth(d, static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
}

}  // namespace penink
