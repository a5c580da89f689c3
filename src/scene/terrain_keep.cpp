#include "scene/terrain_keep.hpp"

#include <chrono>
#include <filesystem>
#include <future>
#include <iostream>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/drainage_memory.hpp"
#include "input/dem_reader.hpp"

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

bool TerrainKeep::build_side_by_side(const Scene& scene, const Log& log, double from_cells) {
    if (!scene.lines.creases.enabled && !scene.lines.ridges.enabled) return false;
    const DemKey key = key_of(scene);
    if ((stored_ && key == stored_key_) || (drainage_ && key == drainage_key_)) return false;
    const std::string& dem = scene.source.dem;
    const std::string& dir = scene.terrain.cache_dir;
    std::error_code ec;
    for (const std::string& p : {dem + ".lod", terrain_cache_path(dem, dir), dem + ".dv", drainage_cache_path(dem, dir)})
        if (std::filesystem::exists(std::filesystem::symlink_status(p, ec))) return false;
    DemSize size;
    try {
        size = read_dem_size(dem);
    } catch (const Error&) {  // named by the terrain cache's build, one after the other
        return false;
    }
    if (double(size.cols) * double(size.rows) <= from_cells) return false;
    if (!cache_builds_fit_together(size.cols, size.rows, drainage_factor_for(size.cols, size.rows, 0), memory_budget(0)))
        return false;
    const TerrainCacheKey dem_key = terrain_cache_key(dem);  // both caches' key: the DEM hashed once
    announce_cache_build(std::cerr, CacheKind::terrain, size.cols, size.rows);
    const auto t0 = std::chrono::steady_clock::now();
    std::future<StoredTerrain> terrain =  // silent: its log lines would cut the drainage build's
        std::async(std::launch::async, [dem, dir, dem_key] { return open_stored_terrain(dem, Log{}, dir, false, &dem_key); });
    Terrain grid;  // all a drainage build that reads the DEM needs before it does
    grid.cols = size.cols, grid.rows = size.rows, grid.source = dem;
    std::optional<DrainageLineSource> source;
    try {
        source = scene_drainage(scene, grid, log, &dem_key);
    } catch (...) {
        terrain.get();  // the terrain cache's error first, as one after the other
        throw;
    }
    StoredTerrain built = terrain.get();
    log.info("terrain: built " + terrain_cache_path(dem, dir) + " beside the drainage database (" +
             std::to_string(int(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count())) +
             " ms for both)");
    stored_ = std::move(built), stored_key_ = key, sea_pyramid_.reset();
    drainage_.reset();
    if (source) {
        read_whole_when_damaged(*source, scene, *stored_, log);
        drainage_ = std::make_shared<const DrainageLineSource>(std::move(*source));
    }
    drainage_key_ = key, drainage_routing_ = scene.terrain.drainage_routing;
    return true;
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
