#include "scene/terrain_keep.hpp"

#include <filesystem>

#include "scene/terrain_frames.hpp"

namespace penink {

TerrainKeep::DemKey TerrainKeep::key_of(const Scene& scene) {
    DemKey k{scene.source.dem, scene.terrain.cache_dir};
    std::error_code ec;  // a DEM that cannot be read is reported by open_stored_terrain
    k.size = std::filesystem::file_size(scene.source.dem, ec);
    const auto t = std::filesystem::last_write_time(scene.source.dem, ec);
    if (!ec) k.mtime_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
    return k;
}

const StoredTerrain& TerrainKeep::stored(const Scene& scene, const Log& log) {
    const DemKey key = key_of(scene);
    if (!stored_ || !(key == stored_key_)) {
        stored_.reset(), sea_pyramid_.reset();
        stored_ = open_stored_terrain(scene.source.dem, log, scene.terrain.cache_dir);
        stored_key_ = key;
    }
    return *stored_;
}

SceneTerrain TerrainKeep::terrain(Scene& scene, const Log& log) {
    SceneTerrain t = scene_terrain(scene, stored(scene, log), log, sea_pyramid_ ? &*sea_pyramid_ : nullptr);
    if (t.stored.lod.error.data() != stored_->lod.error.data()) sea_pyramid_ = t.stored.lod;  // built for its sea level
    return t;
}

std::shared_ptr<const DrainageLineSource> TerrainKeep::drainage(const Scene& scene, const SceneTerrain& dem,
                                                                const Log& log) {
    if (!scene.lines.creases.enabled && !scene.lines.ridges.enabled) return nullptr;
    const DemKey key = key_of(scene);
    if (!drainage_ || !(key == drainage_key_) || scene.terrain.drainage_routing != drainage_routing_) {
        drainage_.reset();
        std::optional<DrainageLineSource> source = scene_drainage(scene, dem, log);
        if (source) drainage_ = std::make_shared<const DrainageLineSource>(std::move(*source));
        drainage_key_ = key, drainage_routing_ = scene.terrain.drainage_routing;
    }
    return drainage_;
}

}  // namespace penink
