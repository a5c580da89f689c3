#include "render/terrain_renderer.hpp"

#include <chrono>
#include <cmath>

namespace penink {

TerrainRenderer::TerrainRenderer(const GlApi& gl, const SurfaceMesh& mesh, int width, int height)
    : gl_(&gl), geometry_(gl, mesh), tft_aft_(gl, width, height), sil_(gl, width, height) {
    check_gl_error(gl, "terrain renderer set-up");
}

FrameImages TerrainRenderer::render(const Camera& camera, const FrameOptions& options) {
    FrameImages out;
    const TftAftTimes surface = tft_aft_.draw(geometry_, camera, options.tessellation,
                                              options.separate_passes);
    check_gl_error(*gl_, "TFT/AFT pass");
    out.times.tft = surface.tft_ms, out.times.aft = surface.aft_ms;
    out.times.sil = sil_.draw(tft_aft_.toward_texture(), tft_aft_.away_texture(),
                              options.silhouette_min_gap);
    check_gl_error(*gl_, "SIL pass");
    const auto t0 = std::chrono::steady_clock::now();
    const int w = tft_aft_.width(), h = tft_aft_.height();
    out.toward = read_depth_image(*gl_, tft_aft_.toward_texture(), w, h);
    out.away = read_depth_image(*gl_, tft_aft_.away_texture(), w, h);
    out.silhouettes = read_pixel_mask(*gl_, sil_.silhouette_texture(), w, h);
    check_gl_error(*gl_, "read-back");
    out.times.readback = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

PixelMask coverage_mask(const FrameImages& images) {
    PixelMask m;
    m.width = images.toward.width, m.height = images.toward.height;
    m.on.resize(images.toward.depth.size());
    for (std::size_t i = 0; i < m.on.size(); ++i)
        m.on[i] = std::isfinite(images.toward.depth[i]) || std::isfinite(images.away.depth[i]);
    return m;
}

}  // namespace penink
