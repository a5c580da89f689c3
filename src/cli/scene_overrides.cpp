#include "cli/scene_overrides.hpp"

#include <CLI/CLI.hpp>

namespace penink {

void add_scene_override_options(CLI::App* cmd, SceneOverrides& o) {
    cmd->add_option("--style", o.style, "Style name (technical, field-sketch) or a style .toml file");
    cmd->add_option("--width", o.width, "Image width in pixels (overrides the scene)");
    cmd->add_option("--height", o.height, "Image height in pixels (overrides the scene)");
    cmd->add_option("--seed", o.seed, "Seed of the sketchy perturbation (same seed, same output)");
    cmd->add_option("--vertical-exaggeration", o.vertical_exaggeration, "Scale elevations by this factor");
    cmd->add_option("--gl", o.gl, "OpenGL backend: osmesa (software, default) or egl (GPU)")
        ->check(CLI::IsMember({"osmesa", "egl"}));
}

Scene load_scene_with_overrides(const SceneOverrides& o) {
    Scene scene = load_scene(o.input);
    if (o.width != SceneOverrides::unset) scene.camera.width = o.width;
    if (o.height != SceneOverrides::unset) scene.camera.height = o.height;
    if (o.seed >= 0) scene.seed = std::uint64_t(o.seed);
    if (o.vertical_exaggeration != 0.0) scene.vertical_exaggeration = o.vertical_exaggeration;
    if (!o.style.empty()) scene.style = o.style;
    validate_scene(scene);
    return scene;
}

}  // namespace penink
