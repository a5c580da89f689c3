// What a command does with a scene's style (resolved by load_scene: scene.hpp's SceneStyle) around
// drawing: the object-space sketchiness of creases and ridges is the terrain path's (perturbed
// within the surface plane, Potter et al., "NPR-Style 3D Line Textures" 4.3: drainage_lines.cpp),
// the rest split between the lines stage (finish_drawing: overshoot, repeats, thinning,
// image-space sketch) and export.
#pragma once
#include <cstdint>

#include "export/style.hpp"
#include "lines/finish_drawing.hpp"

namespace penink {

// Finishing options from the style; with object_space_terrain_lines, creases and ridges are
// marked object-space (already perturbed and repeated by the terrain path).
FinishOptions finish_options(const Style& style, std::uint64_t seed, bool object_space_terrain_lines);

}  // namespace penink
