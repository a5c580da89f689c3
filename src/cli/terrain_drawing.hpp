// The whole terrain path of `penink render`: DEM -> terrain cropped to the view -> PN surface
// -> GPU passes (TFT/AFT, SIL) -> traced, simplified polylines in the named layers of a
// Drawing (image pixels, eye distances in metres), with per-pass timings.
#pragma once
#include "cli/log.hpp"
#include "cli/scene.hpp"
#include "core/drawing.hpp"
#include "render/gl_context.hpp"
#include "render/terrain_renderer.hpp"

namespace penink {

struct TerrainDrawingResult {
    Drawing drawing;
    Camera camera;
    PassTimings times;     // GPU ms per pass
    double trace_ms = 0;   // CPU: read-back images -> polylines
    std::size_t cells = 0, triangles = 0;
};

TerrainDrawingResult draw_terrain(const Scene& scene, GlContext& context, const Log& log);

// Surface mask rings and silhouette/outline strokes from one frame's images (lines stage).
void add_frame_lines(const FrameImages& images, Drawing& drawing);

}  // namespace penink
