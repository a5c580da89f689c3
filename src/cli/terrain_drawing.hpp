// The whole terrain path of `penink render`: DEM -> terrain cropped to the view -> PN surface
// -> GPU passes (TFT/AFT, SIL) -> traced, simplified polylines in the named layers of a
// Drawing (image pixels, eye distances in metres), with per-pass timings.
#pragma once
#include <future>
#include <memory>

#include "cli/drainage_lines.hpp"
#include "cli/scene_drawing.hpp"

namespace penink {

SceneDrawing draw_terrain(const Scene& scene, GlContext& context, const Log& log);

// A terrain set up once and drawn in many frames (render, batch, bench): its surface mesh and GPU
// copy, and its drainage lines. `terrain` is what gets modelled (cropped to the view for a single
// frame, the whole DEM for a flight); `dem` is the whole DEM the drainage cache belongs to.
class TerrainFrames {
public:
    TerrainFrames(GlContext& context, const Scene& scene, const Terrain& dem, Terrain terrain,
                  int width, int height, const Log& log);
    TerrainFrames(const TerrainFrames&) = delete;  // the line preparation thread holds &mesh_
    TerrainFrames& operator=(const TerrainFrames&) = delete;
    ~TerrainFrames();
    // One frame: camera plus the scene's per-frame values (light, creases, ridges, tessellation).
    SceneDrawing draw(const Camera& camera, const Scene& frame);
    const SurfaceMesh& mesh() const { return mesh_; }

private:
    GlContext* context_;
    Terrain terrain_;
    SurfaceMesh mesh_;
    TerrainRenderer renderer_;
    std::unique_ptr<DrainageLines> lines_;
    std::future<DrainageLineData> pending_lines_;  // prepared on another core during the first frame
};

// Surface mask rings and silhouette strokes from one frame's images (lines stage), and the
// visible parts of the surface's boundary (the DEM's cut edges) as object-space outline strokes.
void add_frame_lines(const FrameImages& images, const SurfaceMesh& mesh, const Camera& camera,
                     Drawing& drawing);

}  // namespace penink
