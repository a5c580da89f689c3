// The scene layer's one interface to drawing: a FrameSource turns a camera (plus the scene's
// per-frame values: light, creases, ridges, tessellation, silhouette method) into a Drawing,
// whatever the input: a DEM (scene/terrain_frames.hpp: drainage creases and ridges,
// silhouettes) or a triangle mesh (scene/mesh_frames.hpp: PELs, silhouettes, feature edges,
// textures). `penink render` draws one frame of the scene's own view, `batch` one per flight
// record, `bench` one per configuration. Drawings are in image pixels with eye distances in metres
// (world units for meshes); each carries the camera used and per-pass timings.
#pragma once
#include <cstdint>
#include <memory>

#include "core/drawing.hpp"
#include "core/log.hpp"
#include "core/pixel_mask.hpp"
#include "render/gl_context.hpp"
#include "render/terrain_renderer.hpp"
#include "scene/scene.hpp"

namespace penink {

// CPU time of the object-space steps of one mesh frame, milliseconds (scene/mesh_frames.hpp).
struct MeshLineTimings {
    double normals = 0, pel_geometry = 0, pel = 0, silhouettes = 0, features = 0, textures = 0,
           visibility = 0;
};

struct SceneDrawing {
    Drawing drawing;
    Camera camera;
    PassTimings times;     // GPU ms per pass
    double trace_ms = 0;   // CPU: read-back images -> polylines (a mesh: all its object-space lines)
    double hachure_ms = 0; // CPU: the hachures (terrains)
    MeshLineTimings lines; // a mesh frame's object-space steps (parts of trace_ms)
    std::size_t cells = 0, triangles = 0;
    // Of a terrain cache read on demand (core/checked_blocks.hpp): bytes of its arrays read so
    // far, and all of them; 0 for nodes in memory.
    std::uint64_t cache_bytes_read = 0, cache_bytes = 0;
    PixelMask silhouette_mask;  // the frame's silhouette pixels before tracing (terrains)
    DepthImage toward;          // the frame's nearest-surface eye distances (terrains; tone measure)
};

class FrameSource {
public:
    virtual ~FrameSource() = default;
    virtual SceneDrawing draw(const Camera& camera, const Scene& frame) = 0;
};

// A scene's input set up for its own view: the camera (placed, or auto-framed) and the frames.
struct SceneView {
    Camera camera;
    std::unique_ptr<FrameSource> frames;
};

// True when the scene's input is a mesh (.obj .ply .off, or a scene with [mesh]).
bool is_mesh_scene(const Scene& scene);

class TerrainKeep;

// The scene's view; a terrain scene's "auto" vertical exaggeration is resolved into `scene`.
// `keep`: what a terrain scene's view takes from and leaves to the views drawn after it
// (scene/terrain_keep.hpp); none for a mesh.
SceneView open_scene_view(Scene& scene, GlContext& context, const Log& log, TerrainKeep* keep = nullptr);

// One frame of the scene's own view. A block of the terrain cache found damaged while the frame
// reads it (DamagedBlockError, surface/terrain_cache.hpp) is logged, the cache removed (and
// forgotten by `keep`) and the frame drawn again from a rebuilt one; damage found again (a cache
// that cannot be removed) is the error. Frames drawn from an open view (flights, batches) report
// such damage as the error.
SceneDrawing draw_scene(Scene& scene, GlContext& context, const Log& log, TerrainKeep* keep = nullptr);

}  // namespace penink
