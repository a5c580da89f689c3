#include "scene/scene_memory.hpp"

#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "drainage/drainage_memory.hpp"
#include "input/dem_reader.hpp"
#include "scene/cache_build_estimate.hpp"
#include "scene/frame_source.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

namespace {

// The image's buffers.
double image_bytes(const Scene& scene) {
    return double(scene.view.camera.width) * double(scene.view.camera.height) * render_bytes_per_pixel;
}

// A cols x rows DEM's drawing from its caches, the image aside: the terrain cache's build and,
// with a sea level, the pyramid rebuilt for it over the padded square (a long thin DEM's square is
// far larger than its nodes).
double dem_bytes(const Scene& scene, int cols, int rows) {
    const double side = std::ldexp(1.0, lod_padded_levels(cols, rows)) + 1.0;
    const double water = scene.terrain.sea_level ? side * side * water_lod_bytes_per_padded_node : 0.0;
    return terrain_cache_estimate(cols, rows).peak_bytes + water;
}

}  // namespace

double scene_frame_bytes(const Scene& scene, int cols, int rows) { return dem_bytes(scene, cols, rows) + image_bytes(scene); }

void check_scene_memory(const Scene& scene, std::uint64_t max_memory) {
    const double image = image_bytes(scene);
    const std::string& file = scene.source.file.empty() ? (scene.source.mesh.empty() ? scene.source.dem : scene.source.mesh) : scene.source.file;
    const std::string image_what = "drawing a " + std::to_string(scene.view.camera.width) + "x" +
                                   std::to_string(scene.view.camera.height) + " image";
    if (is_mesh_scene(scene) || scene.source.dem.empty()) {
        if (max_memory > 0 || image > double(check_memory_from_bytes) * 64) check_memory("scene", file, image_what, image, memory_budget(max_memory));
        return;
    }
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(scene.source.dem, ec);
    if (max_memory == 0 && (ec || bytes < check_memory_from_bytes)) {
        if (image > double(check_memory_from_bytes) * 64) check_memory("scene", file, image_what, image, memory_budget(0));
        return;
    }
    const std::uint64_t budget = memory_budget(max_memory);
    const DemSize size = read_dem_size(scene.source.dem);
    // the caches' builds (built side by side: cache_build_estimate.hpp): the terrain cache's
    // always, for what a frame from the caches holds too (0.4 GB for 117 M cells, whose frame holds
    // 0.53 GB); the drainage database's where the scene draws creases or ridges and the render
    // will not read one (the DEM as the terrain cache recorded it, a database of that DEM's
    // fingerprint: scene_drainage_cached); with a sea level, the pyramid rebuilt for it over the
    // padded square (a long thin DEM's square is far larger than its nodes).
    const bool lines = scene.lines.creases.enabled || scene.lines.ridges.enabled;
    const int factor = drainage_factor_for(size.cols, size.rows, 0);
    const std::optional<TerrainCacheKey> known = lines ? known_terrain_key(scene.source.dem, scene.terrain.cache_dir) : std::nullopt;
    const bool drainage_cached = known && scene_drainage_cached(scene, *known, size.cols, size.rows);
    const double drainage = lines && !drainage_cached ? drainage_build_bytes(size.cols, size.rows, factor) : 0.0;
    const double dem = dem_bytes(scene, size.cols, size.rows) + drainage;
    if (budget > 0 && dem > double(budget) && dem - drainage <= double(budget))  // the creases' build alone does not fit
        throw Error("drainage", scene.source.dem,
                    "the drainage grid of the creases and ridges at factor " + std::to_string(factor) + " (" +
                        drainage_grid_size(size.cols, size.rows, factor) + " points) would need about " +
                        format_bytes(dem) + " of memory, " + format_bytes(double(budget)) +
                        " available (--max-memory); without creases and ridges ([creases] and [ridges] enabled = "
                        "false) the drawing needs about " + format_bytes(dem - drainage));
    check_memory("input", scene.source.dem,
                 "drawing the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) + " nodes", dem, budget);
    check_memory("scene", file, image_what + " of the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) + " nodes",
                 dem + image, budget);
}

}  // namespace penink
