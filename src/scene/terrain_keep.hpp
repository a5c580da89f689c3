// What a process that draws one terrain scene after another keeps between them (penink preview's
// drawing thread, where every frame is a scene loaded from the view's file): the DEM's stored
// terrain (open_stored_terrain, read once per DEM file and cache folder), the pyramid built for a
// sea level (the last one), the drainage lines' source (scene_drainage, once per DEM, routing and
// cache folder) and the GPU passes (terrain_frames.hpp's TerrainGpuKeep: the renderers of the image
// sizes drawn last, the DM passes).
// A DEM whose size or modification time changed since is read again, with all that came from it.
// A scene opened through a keep draws what open_terrain_view draws without one (the same values,
// computed the same way; only what would be read or built again is not).
// Not thread-safe; its renderers belong to the GL context current on the thread that uses it,
// and it must be destroyed before that context.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drainage/line_selection.hpp"
#include "scene/cache_build_estimate.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

class TerrainKeep {
public:
    // A DEM's first drawing: where the scene draws creases or ridges, the DEM has more than
    // `from_cells` cells, neither its terrain cache nor its drainage database is on disk (beside it or
    // in the cache folder) and the memory available holds both builds' estimated peaks, the
    // drainage database is built on this thread (with its progress) while the terrain cache is
    // built on another (most drainage stages keep one core: filling, flats, ties, accumulation),
    // and both are kept, as stored() and drainage() would keep them (the same files and values).
    // Returns whether it built them; otherwise nothing is done and stored() and drainage() build
    // them one after the other. A DEM that cannot be read fails in the terrain cache's build, as
    // it would one after the other (its error is the one thrown when both fail).
    bool build_side_by_side(const Scene& scene, const Log& log, double from_cells = estimate_from_cells);
    // open_stored_terrain of the scene's DEM and cache folder, read when not kept.
    const StoredTerrain& stored(const Scene& scene, const Log& log);
    // open_scene_terrain(scene, log), from what is kept.
    SceneTerrain terrain(Scene& scene, const Log& log);
    // scene_drainage(scene, dem, log) shared, from what is kept; null when the scene draws neither
    // creases nor ridges.
    std::shared_ptr<const DrainageLineSource> drainage(const Scene& scene, const SceneTerrain& dem, const Log& log);
    TerrainGpuKeep& gpu() { return gpu_; }
    // Drops the stored terrain and its pyramid (a cache found damaged): the next frame reads it again.
    void forget_terrain() { stored_.reset(), sea_pyramid_.reset(); }

private:
    // What identifies a DEM's stored terrain: its path, size and modification time, the cache folder.
    struct DemKey {
        std::string dem, cache_dir;
        std::uintmax_t size = 0;
        std::int64_t mtime_ns = 0;
        bool operator==(const DemKey&) const = default;
    };
    static DemKey key_of(const Scene& scene);

    DemKey stored_key_;
    std::optional<StoredTerrain> stored_;
    std::optional<TerrainLod> sea_pyramid_;  // of stored_, for its sea level
    DemKey drainage_key_;
    std::string drainage_routing_;
    std::shared_ptr<const DrainageLineSource> drainage_;
    TerrainGpuKeep gpu_;
};

}  // namespace penink
