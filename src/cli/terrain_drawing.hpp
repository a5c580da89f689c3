// The whole terrain path of `penink render`: DEM -> terrain cropped to the view -> PN surface
// -> GPU passes (TFT/AFT, SIL) -> traced, simplified polylines in the named layers of a
// Drawing (image pixels, eye distances in metres), with per-pass timings.
#pragma once
#include "cli/scene_drawing.hpp"

namespace penink {

SceneDrawing draw_terrain(const Scene& scene, GlContext& context, const Log& log);

// Surface mask rings and silhouette strokes from one frame's images (lines stage), and the
// visible parts of the surface's boundary (the DEM's cut edges) as object-space outline strokes.
void add_frame_lines(const FrameImages& images, const SurfaceMesh& mesh, const Camera& camera,
                     Drawing& drawing);

}  // namespace penink
