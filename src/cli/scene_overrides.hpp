// The command-line options that override a scene's values (shared by render and batch): their
// CLI11 options, filling a SceneOverrides (scene/scene_overrides.hpp).
#pragma once
#include "scene/scene_overrides.hpp"

namespace CLI {
class App;
}

namespace penink {

// --width --height --style --seed --vertical-exaggeration --sea-level --map --scale --title --grid
// --no-furniture --gl --max-memory
// --position --elevation --azimuth --altitude --fov --target --distance
void add_scene_override_options(CLI::App* cmd, SceneOverrides& o);

}  // namespace penink
