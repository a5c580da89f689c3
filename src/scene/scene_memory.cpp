#include "scene/scene_memory.hpp"

#include <cmath>
#include <filesystem>

#include "core/memory_budget.hpp"
#include "drainage/drainage_memory.hpp"
#include "input/dem_reader.hpp"
#include "scene/frame_source.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

void check_scene_memory(const Scene& scene, std::uint64_t max_memory) {
    const double image = double(scene.view.camera.width) * double(scene.view.camera.height) * render_bytes_per_pixel;
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
    const double drainage = drainage_build_bytes(size.cols, size.rows, drainage_factor_for(size.cols, size.rows, 0));
    // the level-of-detail pyramid's errors over the padded square (a long thin DEM's square is
    // far larger than its nodes), and the pyramid rebuilt for a sea level
    const double side = std::ldexp(1.0, lod_padded_levels(size.cols, size.rows)) + 1.0;
    double water = side * side * lod_bytes_per_padded_node;
    if (scene.terrain.sea_level) water += side * side * water_lod_bytes_per_padded_node;
    const double dem = size.nodes() * render_bytes_per_node + drainage + water;
    check_memory("input", scene.source.dem,
                 "drawing the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) + " nodes", dem, budget);
    check_memory("scene", file, image_what + " of the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) + " nodes",
                 dem + image, budget);
}

}  // namespace penink
