// The input files of a scene (scene_inputs.hpp).
#include "scene/scene_inputs.hpp"

#include "input/dem_side_files.hpp"
#include "drainage/drainage_build.hpp"
#include "export/world_file.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

std::vector<NamedInput> dem_inputs(const std::string& dem) {
    std::vector<NamedInput> in;
    if (dem.empty()) return in;
    in.push_back({dem, "the DEM"});
    for (std::string& f : dem_side_files(dem)) in.push_back({std::move(f), "the DEM's side file"});
    return in;
}

std::vector<NamedInput> scene_inputs(const Scene& s) {
    std::vector<NamedInput> in = dem_inputs(s.source.dem);
    if (!s.source.file.empty()) in.push_back({s.source.file, "the scene"});
    if (!s.source.mesh.empty()) in.push_back({s.source.mesh, "the mesh"});
    if (!s.style.name.empty()) in.push_back({s.style.name, "the style"});
    if (!s.source.dem.empty()) {
        in.push_back({drainage_cache_path(s.source.dem, s.terrain.cache_dir), "the DEM's drainage cache"});
        in.push_back({terrain_cache_path(s.source.dem, s.terrain.cache_dir), "the DEM's terrain cache"});
    }
    return in;
}

void check_outputs_are_not_inputs(const std::vector<std::string>& outputs, const std::vector<NamedInput>& inputs) {
    std::vector<std::string> all = outputs;
    for (const std::string& p : outputs)
        for (std::string& f : raster_side_file_names(p)) all.push_back(std::move(f));
    check_outputs_not_inputs("export", all, inputs);
}

}  // namespace penink
