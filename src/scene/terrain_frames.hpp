// The terrain frames of the scene layer: DEM -> terrain cropped to the view -> PN surface
// -> GPU passes (TFT/AFT, SIL; DM for creases, ridges and the coastline) or the CPU object-space silhouettes
// -> traced, simplified polylines in the named layers of a Drawing (image pixels, eye
// distances in metres), with per-pass timings.
#pragma once
#include <future>
#include <memory>
#include <optional>

#include "scene/coastline_lines.hpp"
#include "scene/drainage_lines.hpp"
#include "scene/frame_source.hpp"
#include "scene/terrain_view.hpp"
#include "surface/surface_mesh.hpp"
#include "render/terrain_renderer_pool.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

class TerrainKeep;

// What TerrainFrames leave on the GPU for the TerrainFrames that follow on the same context
// (terrain_keep.hpp): a renderer per image size drawn last and the drainage lines' DM passes, their
// programs compiled once (llvmpipe compiles a program's shaders again for every new program
// object, at its first draw); each frame uploads its own mesh and lines into them.
struct TerrainGpuKeep {
    TerrainRendererPool renderers;
    std::unique_ptr<DrainageLines> lines;
};

// The scene's DEM read, its camera placed, the DEM cropped to that view and set up for frames.
// With a keep (terrain_keep.hpp; it must outlive the view): what it holds is used, and what is
// read or made is kept there.
SceneView open_terrain_view(Scene& scene, GlContext& context, const Log& log, TerrainKeep* keep = nullptr);

// The scene's drainage lines (cached beside the DEM: drainage/drainage_build.hpp), read or built
// with progress on a terminal; none when the scene draws neither creases nor ridges. A valid
// cache is checked whole but only its line records and index are held: the frames read the
// vertices of the lines they select from the file (DrainageLineSource).
// `dem`: the DEM's grid (its node arrays, when held unexaggerated, spare a build reading it again);
// `key` (when given): the DEM's identity the terrain cache was opened with this run, whose
// content hash the drainage cache's fingerprint takes instead of hashing the file again (a 117 M
// cell DEM: 466 MB, about 0.2 s).
std::optional<DrainageLineSource> scene_drainage(const Scene& scene, const Terrain& dem, const Log& log,
                                                 const TerrainCacheKey* key = nullptr);
// Whether a drainage database that scene_drainage would read for a cols x rows DEM whose terrain
// cache key is `key` is there (beside the DEM, or where the render keeps it): its header's
// fingerprint alone read (peek_drainage_fingerprint), so a database that then fails to read is
// built after all (load_or_build_drainage checks its memory then).
bool scene_drainage_cached(const Scene& scene, const TerrainCacheKey& key, int cols, int rows);
// The same from the DEM's stored terrain (its node arrays when in memory, else its grid; its key),
// with read_whole_when_damaged; a terrain read from its cache file gives the crease tiles' first
// build the DEM's heights by blocks (terrain_node_heights).
std::optional<DrainageLineSource> scene_drainage(const Scene& scene, const SceneTerrain& dem, const Log& log);
// The heights of a terrain read from its cache file, a row's span at a time (GridNodes::read_heights:
// blocks read, checked and decoded without being kept, no node's x, y made; the storage kept
// alive): what building crease tiles reads of a DEM the drainage cache refers to, where the
// stems' walks reach (StoredCreases::use_node_heights), instead of reading the whole DEM again.
NodeHeights terrain_node_heights(const StoredTerrain& t);
// What a first build of crease tiles from the drainage cache checks before it decodes anything
// (StoredCreases::before_first_decode, given the drainage grid's cols x rows points) for a
// dem_cols x dem_rows DEM: throws Error("drainage", DEM, "building the crease tiles of a view not
// drawn before (the drainage grid's CxR points) would need about N of memory, B available
// (--max-memory)") where N, crease_tiles_build_bytes with, under --max-memory
// (scene.terrain.max_memory), what check_scene_memory counted for the frame (scene_frame_bytes),
// exceeds --max-memory, else the memory the system has available then.
std::function<void(int cols, int rows)> crease_tiles_memory_check(const Scene& scene, int dem_cols, int dem_rows);
// Sets source.read_whole (when its vertices are read from the file): the cache read whole, or
// rebuilt, from the DEM's stored terrain `dem` (its grid and key), once found damaged while drawn.
void read_whole_when_damaged(DrainageLineSource& source, const Scene& scene, const StoredTerrain& dem, const Log& log);

// The box of drainage lines a modelled terrain's frames select from (prepare_drainage_lines): its
// plan extent, vertical exaggeration and sea level.
LineBox frame_line_box(const FrameTerrain& terrain);

// The drainage lines of the scene's view (its DEM's caches read, its camera placed), prepared as
// its first frame prepares them, without a GL context: the crease tiles that frame reads are
// built and written where the render keeps them (beside the drainage cache). Returns the tile
// files written (0 where the scene draws no creases, or they are there already). `built`: the
// network of the build in this process that wrote the drainage cache (StoredCreases::
// use_built_network), which the first stems are then built from.
std::size_t write_view_crease_tiles(Scene& scene, const Log& log, BuiltNetworkHandle built = {});

// A terrain set up once and drawn in many frames (render, batch, bench): its level-of-detail
// pyramid (surface/terrain_lod.hpp), from which each frame selects the mesh its camera needs
// ([surface] tolerance_px; 0 = the full-resolution mesh), its GPU copy, and its drainage lines.
// `terrain` is what gets modelled: the nodes (in memory or read on demand from the terrain cache) and the
// window of them the frames may see (the view's for a single frame, the union of the frames'
// windows for a flight), which bounds the drainage lines read; `drainage` holds the lines of the
// whole DEM (scene_drainage).
class TerrainFrames : public FrameSource {
public:
    // `culling`: the cameras the frames will use and the screen size below which a crease or
    // ridge cannot be drawn (prepare_drainage_lines); default: every line of the modelled box.
    TerrainFrames(GlContext& context, std::optional<DrainageLineSource> drainage, FrameTerrain terrain, int width,
                  int height, const Log& log, LineCulling culling = {});
    // The same with drainage lines shared with other frame sources (null: none) and, when given,
    // the renderer and DM passes taken from `gpu` (which must outlive the frames) instead of made;
    // `log` gets the lines' preparation time and the creases built with the first frame.
    TerrainFrames(GlContext& context, std::shared_ptr<const DrainageLineSource> drainage, FrameTerrain terrain,
                  int width, int height, LineCulling culling, TerrainGpuKeep* gpu, const Log& log = {});
    // A Terrain in memory, all of it modelled (frame_terrain).
    TerrainFrames(GlContext& context, std::optional<DrainageLineSource> drainage, Terrain terrain, int width, int height,
                  const Log& log, LineCulling culling = {});
    TerrainFrames(const TerrainFrames&) = delete;  // the line preparation thread holds &terrain_
    TerrainFrames& operator=(const TerrainFrames&) = delete;
    ~TerrainFrames() override;
    // One frame: camera plus the scene's per-frame values (light, creases, ridges, tessellation,
    // silhouette method).
    SceneDrawing draw(const Camera& camera, const Scene& frame) override;
    // The modelled terrain (local metres, exaggerated z).
    const FrameTerrain& terrain() const { return terrain_; }
    // The surface mesh of the last frame drawn (empty before the first).
    const SurfaceMesh& mesh() const { return mesh_; }

private:
    // The frame's surface: the level-of-detail selection, or the whole grid at tolerance 0.
    SurfaceMesh frame_mesh(const Camera& camera, const Scene& frame) const;

    GlContext* context_;
    FrameTerrain terrain_;
    SurfaceMesh mesh_;
    bool mesh_is_full_ = false;  // mesh_ is (and the renderer holds) the full-resolution mesh
    int width_, height_;
    TerrainGpuKeep* gpu_ = nullptr;              // where renderer_ and lines_ come from; null: made here
    std::shared_ptr<TerrainRenderer> renderer_;  // with the first frame's mesh
    std::unique_ptr<DrainageLines> own_lines_;
    DrainageLines* lines_ = nullptr;             // own_lines_ or gpu_'s
    std::unique_ptr<CoastlineLines> coast_;  // with water: the shore, made with the first frame
    std::future<DrainageLineData> pending_lines_;  // prepared on another core during the first frame
    std::shared_ptr<const DrainageLineSource> drainage_;
    Log log_;
    double lines_ms_ = 0.0;  // the preparation's wall time, set before pending_lines_ is ready
};

// Object-space silhouettes (the exact front/back edges of the CPU PN tessellation, ray-cast
// visibility; Mower's silhouette paper's reference) rasterised at 1 px into a width x height mask.
PixelMask object_space_silhouette_mask(const SurfaceMesh& mesh, const Camera& camera,
                                       const TessellationOptions& tessellation);

// One frame's silhouette mask traced into simplified strokes (image pixels, the occluding
// surface's eye distance), each point moved from its pixel's centre onto the depth edge it
// borders (lines/depth_edge_placement.hpp): the drawn Toward/Away or Adjacency silhouettes,
// before the outline.
std::vector<Stroke> traced_silhouettes(const FrameImages& images);

// Surface mask rings and silhouette strokes from one frame's images (lines stage), and the
// visible parts of the surface's boundary (the DEM's cut edges) as object-space outline strokes,
// each weighed by the depth gap behind it (lines/stroke_weight.hpp).
void add_frame_lines(const FrameImages& images, const SurfaceMesh& mesh, const Camera& camera,
                     Drawing& drawing);

}  // namespace penink
