#include "render/terrain_renderer.hpp"

#include <cmath>

#include "core/stopwatch.hpp"

namespace penink {

TerrainRenderer::TerrainRenderer(const GlApi& gl, const SurfaceMesh& mesh, int width, int height)
    : gl_(&gl), geometry_(gl, mesh), tft_aft_(gl, width, height), sil_(gl, width, height) {
    check_gl_error(gl, "terrain renderer set-up");
}

void TerrainRenderer::set_surface(const SurfaceMesh& mesh) {
    geometry_ = SurfaceGeometry(*gl_, mesh);
    check_gl_error(*gl_, "surface upload (" + std::to_string(mesh.tri.size()) + " triangles)");
}

// Runs the chosen GPU silhouette method; returns its time (ms).
double TerrainRenderer::silhouettes(const Camera& camera, const FrameOptions& options, FrameImages& out) {
    const int w = tft_aft_.width(), h = tft_aft_.height();
    switch (options.silhouette_method) {
        case SilhouetteMethod::toward_away:
            return sil_.draw(tft_aft_.toward_texture(), tft_aft_.away_texture(), options.silhouette_min_gap);
        case SilhouetteMethod::adjacency: {
            if (!adjacency_) adjacency_ = std::make_unique<IdAdjacencySilPass>(*gl_, w, h);
            const IdAdjacencyTimes t = adjacency_->draw(geometry_, camera, options.tessellation, tft_aft_.toward_texture(),
                                                        tft_aft_.away_texture(), options.adjacency);
            out.times.sil_ids = t.ids_ms;
            return t.ids_ms + t.pixels_ms;
        }
        case SilhouetteMethod::edge_walk: {
            if (!edge_walk_) edge_walk_ = std::make_unique<EdgeWalkSilPass>(*gl_, w, h);
            const EdgeWalkTimes t = edge_walk_->draw(geometry_, camera, options.tessellation, tft_aft_.toward_texture(),
                                                      tft_aft_.away_texture(), options.edge_walk);
            out.times.sil_ids = t.ids_ms;
            return t.ids_ms + t.detect_ms + t.walk_ms + t.lines_ms;
        }
        case SilhouetteMethod::object_space:  // drawn by the caller on the CPU
            return 0.0;
    }
    return 0.0;
}

FrameImages TerrainRenderer::render(const Camera& camera, const FrameOptions& options) {
    FrameImages out;
    const TftAftTimes surface = tft_aft_.draw(geometry_, camera, options.tessellation,
                                              options.separate_passes);
    check_gl_error(*gl_, "TFT/AFT pass");
    out.times.tft = surface.tft_ms, out.times.aft = surface.aft_ms;
    out.times.sil = silhouettes(camera, options, out);
    check_gl_error(*gl_, "SIL pass");
    const auto t0 = Clock::now();
    const int w = tft_aft_.width(), h = tft_aft_.height();
    out.toward = read_depth_image(*gl_, tft_aft_.toward_texture(), w, h);
    out.away = read_depth_image(*gl_, tft_aft_.away_texture(), w, h);
    if (options.silhouette_method == SilhouetteMethod::toward_away)
        out.silhouettes = read_pixel_mask(*gl_, sil_.silhouette_texture(), w, h);
    else if (options.silhouette_method == SilhouetteMethod::adjacency)
        out.silhouettes = read_pixel_mask(*gl_, adjacency_->silhouette_texture(), w, h);
    else if (options.silhouette_method == SilhouetteMethod::edge_walk)
        out.silhouettes = read_pixel_mask(*gl_, edge_walk_->silhouette_texture(), w, h);
    check_gl_error(*gl_, "read-back");
    out.times.readback = ms_since(t0);
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
