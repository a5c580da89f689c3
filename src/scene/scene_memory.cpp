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
    if (is_mesh_scene(scene) || scene.dem.empty()) return;
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(scene.dem, ec);
    if (max_memory == 0 && (ec || bytes < check_memory_from_bytes)) return;
    const std::uint64_t budget = memory_budget(max_memory);
    const DemSize size = read_dem_size(scene.dem);
    const double drainage = drainage_points(size.cols, size.rows, drainage_factor_for(size.cols, size.rows, 0)) *
                            drainage_bytes_per_point;
    double water = 0.0;  // the pyramid rebuilt for a sea level, over the padded square
    if (scene.sea_level) {
        const double side = std::ldexp(1.0, lod_padded_levels(size.cols, size.rows)) + 1.0;
        water = side * side * water_lod_bytes_per_padded_node;
    }
    check_memory("input", scene.dem,
                 "drawing the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) + " nodes",
                 size.nodes() * render_bytes_per_node + drainage + water, budget);
}

}  // namespace penink
