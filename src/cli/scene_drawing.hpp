// Draws a scene into a Drawing, whatever its input: a DEM (terrain path: drainage creases and
// ridges, silhouettes) or a triangle mesh (PELs, silhouettes, feature edges, textures).
// The result carries the camera used and per-pass timings for --verbose, bench and batch.
#pragma once
#include "cli/log.hpp"
#include "cli/scene.hpp"
#include "core/drawing.hpp"
#include "render/gl_context.hpp"
#include "render/terrain_renderer.hpp"

namespace penink {

struct SceneDrawing {
    Drawing drawing;
    Camera camera;
    PassTimings times;     // GPU ms per pass
    double trace_ms = 0;   // CPU: read-back images -> polylines
    std::size_t cells = 0, triangles = 0;
};

// True when the scene's input is a mesh (.obj .ply .off, or a scene with [mesh]).
bool is_mesh_scene(const Scene& scene);

SceneDrawing draw_scene(const Scene& scene, GlContext& context, const Log& log);

}  // namespace penink
