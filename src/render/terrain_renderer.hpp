// Renders one frame of a terrain surface through the GPU passes (TFT/AFT, SIL) and reads the
// results back for the lines stage: toward/away eye-distance images (metres, row 0 = top) and
// the silhouette pixel mask, with each pass's GPU time (GL timer queries, as the paper's Table 3).
#pragma once
#include <memory>

#include "core/camera.hpp"
#include "lines/pixel_mask.hpp"
#include "render/readback.hpp"
#include "render/sil.hpp"
#include "render/surface_geometry.hpp"
#include "render/tft_aft.hpp"

namespace penink {

struct FrameOptions {
    TessellationOptions tessellation;
    bool separate_passes = false;  // TFT and AFT as two passes (paper) instead of one combined
    float silhouette_min_gap = 0.0f;
};

struct PassTimings {  // milliseconds
    double tft = 0, aft = 0, sil = 0, dm = 0, ridges = 0, lay = 0, readback = 0;
};

struct FrameImages {
    DepthImage toward, away;  // eye distance, +inf where no fragment
    PixelMask silhouettes;
    PassTimings times;
};

class TerrainRenderer {
public:
    TerrainRenderer(const GlApi& gl, const SurfaceMesh& mesh, int width, int height);
    FrameImages render(const Camera& camera, const FrameOptions& options);
    const GlApi& gl() const { return *gl_; }
    const TftAftPass& surface_pass() const { return tft_aft_; }

private:
    const GlApi* gl_;
    SurfaceGeometry geometry_;
    TftAftPass tft_aft_;
    SilPass sil_;
};

// Pixels covered by any surface fragment (toward or away): the surface mask.
PixelMask coverage_mask(const FrameImages& images);

}  // namespace penink
