// Every file a scene reads, with its role, for the check that no output replaces an input
// (core/input_files.hpp): the scene file, the DEM and its side files (input/dem_side_files.hpp),
// the mesh, the style file (when the style names a file), and the DEM's caches (a render reads
// them; only `penink drainage` and the render's own cache writes replace them).
#pragma once
#include <vector>

#include "core/input_files.hpp"
#include "scene/scene.hpp"

namespace penink {

std::vector<NamedInput> scene_inputs(const Scene& scene);

// The DEM and its side files alone.
std::vector<NamedInput> dem_inputs(const std::string& dem);

// Refuses output files (with their raster side files, export/world_file.hpp) that are one of
// `inputs` (check_outputs_not_inputs): Error("export", output, "is the DEM ...").
void check_outputs_are_not_inputs(const std::vector<std::string>& outputs, const std::vector<NamedInput>& inputs);

}  // namespace penink
