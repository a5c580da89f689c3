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
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

class TerrainKeep {
public:
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
