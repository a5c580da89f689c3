// A scene's DEM as frames draw it, and the camera placed over it: the scene's UTM / lon,lat /
// x y position and elevation (metres above datum, scaled with the vertical exaggeration) or, with
// none, the whole DEM framed from the south-west, looking down at 30 degrees (conventions.md).
// An orthographic camera looks along the scene's azimuth and altitude at the whole DEM, or at
// the position's plan point; its image spans the scene's view_width (a map scale) or, with none,
// the DEM fills 0.95 of it.
// Then the part of the DEM the view needs, with near/far planes fitted to it.
//
// The nodes and level-of-detail pyramid come from the terrain cache (surface/terrain_cache.hpp)
// beside the drainage database (`<dem>.lod` where the drainage cache is `<dem>.dv`), whose
// blocks are read and checked as the frames first need them; a missing or stale cache is built
// from the DEM, read unexaggerated, and written.
// One cache serves every vertical exaggeration, view, light and style. Frames: the Terrain's
// local metres, z exaggerated as drawn (GridNodes::at).
#pragma once
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/log.hpp"
#include "input/grid_nodes.hpp"
#include "input/terrain.hpp"
#include "scene/scene.hpp"
#include "surface/terrain_cache.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

inline constexpr double default_view_azimuth = 45.0;    // looking north-east: from the south-west
inline constexpr double default_view_altitude = -30.0;  // looking down

// The scene's DEM, read with its vertical exaggeration (resolved first when it is "auto"); a
// missing-CRS warning (missing_crs_warning, dem_reader.hpp) goes to stderr.
Terrain read_scene_dem(Scene& scene, const Log& log);

// Resolves an "auto" vertical exaggeration (scene.terrain.exaggeration_auto; auto_vertical_exaggeration)
// from the DEM's valid elevation range and plan box (local metres), logged; a number is kept.
void resolve_vertical_exaggeration(Scene& scene, double z_min, double z_max, const glm::dvec2& plan_lo,
                                   const glm::dvec2& plan_hi, const Log& log);

// The terrain cache of a DEM: the drainage cache's path (drainage_cache_path, in `cache_dir`
// when one is given) with .lod for .dv.
std::string terrain_cache_path(const std::string& dem_path, const std::string& cache_dir = "");
// What a DEM's terrain cache is keyed by: the DEM file (as the drainage database's fingerprint)
// and the UTM zone forced on a geographic DEM (none: 0).
// Its identity (input/dem_file_identity.hpp) taken before the DEM is hashed.
TerrainCacheKey terrain_cache_key(const std::string& dem_path);
// The key a terrain cache of the DEM (beside it, then in cache_dir's place: terrain_cache_path)
// recorded with the DEM's identity as it is now: the DEM unchanged since that cache was written,
// its key known without reading the DEM. nullopt when no cache recorded this identity.
std::optional<TerrainCacheKey> known_terrain_key(const std::string& dem_path, const std::string& cache_dir = "");

// The scene's DEM: nodes and pyramid, stored (read from the cache, or from the DEM and cached), drawn
// at the scene's vertical exaggeration, with water below its sea level (GridNodes::sea_level).
// When the sea level lies above the DEM's lowest node, open_scene_terrain replaces the cached
// pyramid by one built (in memory) on the clamped nodes, so the water costs no triangles and the
// pyramid's bounds are those of the surface drawn, water included.
struct SceneTerrain {
    StoredTerrain stored;
    double exaggeration = 1.0;
    std::string file;  // the scene or DEM file named in messages
    double sea_level = -std::numeric_limits<double>::infinity();  // [terrain] sea_level; -inf: none

    GridNodes nodes() const { return stored.drawn(exaggeration, sea_level); }
    // Grid and georeference at the exaggeration (no node arrays).
    Terrain meta() const {
        Terrain t = stored.meta;
        t.vertical_exaggeration = exaggeration;
        return t;
    }
};

// The DEM's stored terrain: read from the cache when a valid one lies beside the DEM (`<dem>.lod`, even in a
// folder render cannot write) or at terrain_cache_path, else built there from the DEM read by
// bands (build_terrain_cache), or where that cannot be (a cache that cannot be written, logged;
// x, y that follow no formula) from the DEM read whole and kept in memory. Throws penink::Error
// (stage "input") for a DEM that cannot be read, (stage "surface") for one whose cache build, or
// whose nodes and pyramid held whole, would not fit the memory available (checked from its header
// before it is read: a long thin DEM's pyramid covers the padded square) and (stage "scene") for a vertical exaggeration that is not a finite number > 0.
// open_scene_terrain resolves the scene's "auto" vertical exaggeration first. A build of a large
// DEM writes its estimate line (announce_cache_build) to stderr first, unless `announce` is false
// (the caller wrote it: a build on another thread, scene/terrain_keep.hpp). `key`: the DEM's
// terrain_cache_key when the caller made it this run (the file is not hashed again); null: made
// here, known_terrain_key's where a cache recorded the DEM as it is (not read), else hashed.
StoredTerrain open_stored_terrain(const std::string& dem_path, const Log& log, const std::string& cache_dir = "",
                                  bool announce = true, const TerrainCacheKey* key = nullptr);
SceneTerrain open_scene_terrain(Scene& scene, const Log& log);
// The same from the DEM's stored terrain opened before (open_stored_terrain, no sea level in its
// pyramid); `sea_pyramid`, when its sea level is the scene's, is the pyramid built for it before
// (a process that draws many scenes of one DEM builds it once).
SceneTerrain scene_terrain(Scene& scene, StoredTerrain stored, const Log& log, const TerrainLod* sea_pyramid = nullptr);

Camera scene_camera(const Scene& scene, const SceneTerrain& terrain);
Camera scene_camera(const Scene& scene, const Terrain& terrain);

// Points the automatic camera frames: every edge node and a subsample of the rest (all nodes up
// to 20000; beyond, every k-th node of every k-th row, about 20000 of them), as drawn; nodes of a
// terrain cache are read without keeping their blocks (GridNodes::read_strided).
std::vector<glm::dvec3> frame_samples(const GridNodes& nodes);
std::vector<glm::dvec3> frame_samples(const Terrain& terrain);

// What a TerrainFrames draws: nodes and pyramid at the drawing's exaggeration (built, or read
// from the cache) and the part of them the frames may see.
struct FrameTerrain {
    Terrain meta;                          // grid and georeference, vertical_exaggeration; no node arrays
    GridNodes nodes;                       // as drawn
    TerrainLod lod;
    std::shared_ptr<const void> storage;   // owns what `nodes` points to
    GridWindow window;                     // the nodes the frames may see
    glm::dvec3 lo{0.0}, hi{0.0};           // bounds of those nodes, drawn metres
    std::size_t cells() const { return std::size_t(std::max(window.cols() - 1, 0)) * std::max(window.rows() - 1, 0); }
};

// A Terrain held in memory at its exaggeration, all of it in view (its pyramid built here).
FrameTerrain frame_terrain(Terrain terrain);
// The window of a FrameTerrain as a Terrain of its own (the nodes copied as drawn).
Terrain window_terrain(const FrameTerrain& terrain);

// The part of the scene's DEM a camera may see: lod_visible_window with a node of margin, its
// bounds within the stored terrain's (exact when the window is the whole DEM); an empty window
// when it sees none.
LodView scene_view_window(const SceneTerrain& terrain, const Camera& camera);
// The union of views (empty windows skipped); the whole DEM with its bounds when `whole`.
LodView view_union(const SceneTerrain& terrain, const std::vector<LodView>& views, bool whole = false);
// The scene's DEM modelled over a view's window.
FrameTerrain frame_terrain(const SceneTerrain& terrain, const LodView& view);

// What the camera sees of the scene's DEM (logged: cells used of all), found on the pyramid
// (lod_visible_window) with a node of margin, near/far planes fitted to its bounds; throws
// penink::Error(stage "scene") when the camera is below the ground or sees none of the DEM.
FrameTerrain terrain_for_view(const SceneTerrain& terrain, Camera& camera, const Scene& scene, const Log& log);

// The terrain cropped to what the camera sees (visible_window, every node visited); the same
// errors. The whole terrain is moved, not copied, when the view sees all of it.
Terrain terrain_for_view(Terrain terrain, Camera& camera, const Scene& scene, const Log& log);

}  // namespace penink
