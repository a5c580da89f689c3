// What a command does with a scene's style around drawing: resolves it (named or file, plus the
// scene's [style] overrides), hands the object-space sketchiness of creases and ridges to the
// terrain path (perturbed within the surface plane, Potter et al., "NPR-Style 3D Line Textures" 4.3), and splits the rest between
// the lines stage (finish_drawing: overshoot, repeats, thinning, image-space sketch) and export.
#pragma once
#include <cstdint>

#include "scene/scene.hpp"
#include "export/style.hpp"
#include "lines/finish_drawing.hpp"

namespace penink {

Style scene_style(const Scene& scene);

// Copies the style's crease/ridge sketch amount and repeats into the scene (terrain path), and the
// hachures' pen width when the scene gives none.
void apply_object_sketch(Scene& scene, const Style& style);

// Finishing options from the style; with object_space_terrain_lines, creases and ridges are
// marked object-space (already perturbed and repeated by the terrain path).
FinishOptions finish_options(const Style& style, std::uint64_t seed, bool object_space_terrain_lines);

}  // namespace penink
