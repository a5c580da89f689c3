#include "cli/scene_overrides.hpp"

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "core/error.hpp"
#include "scene/scene_memory.hpp"

namespace penink {

void add_scene_override_options(CLI::App* cmd, SceneOverrides& o) {
    cmd->add_option("--style", o.style, "Style name (technical, field-sketch, plotter) or a style .toml file");
    cmd->add_option("--width", o.width, "Image width in pixels, 1..16384 (overrides the scene)")
        ->check(number_between(1, max_image_side));
    cmd->add_option("--height", o.height, "Image height in pixels, 1..16384 (overrides the scene)")
        ->check(number_between(1, max_image_side));
    cmd->add_option("--seed", o.seed, "Seed of the sketchy perturbation (same seed, same output)")
        ->check(number_between(0, 9007199254740992.0));
    cmd->add_option("--vertical-exaggeration", o.vertical_exaggeration,
                    "Scale elevations by this factor, (0, 1000], or auto (from the relief and extent; the default for DEMs)")
        ->check(positive_at_most_or_auto(max_vertical_exaggeration));
    cmd->add_flag("--map", o.map, "Orthographic plan view of the whole DEM, north up");
    cmd->add_option("--scale", o.scale, "Map scale 1:N on the page set by --page/--dpi/--margin (orthographic views)")
        ->check(map_scale_check());
    cmd->add_option("--sea-level", o.sea_level,
                    "Draw the DEM below this elevation (its units, unexaggerated) as water, with a coastline")
        ->check(number_between(-1e7, 1e7));
    cmd->add_option("--gl", o.gl, "OpenGL backend: osmesa (software, default) or egl (GPU)")
        ->check(CLI::IsMember({"osmesa", "egl"}));
    add_max_memory_option(cmd, o.max_memory);
    const char* place = "(\"LON,LAT\", \"EASTING NORTHING ZONE\" such as \"588497 4589846 18N\", or \"X Y\" in the DEM's CRS)";
    cmd->add_option("--position", o.position, std::string("Camera position ") + place + "; goes with --elevation");
    cmd->add_option("--elevation", o.elevation, "Camera elevation, metres above the DEM's datum (unexaggerated)")
        ->check(number_between(-1e7, 1e7));
    cmd->add_option("--azimuth", o.azimuth, "View direction, degrees clockwise from grid north")
        ->check(number_between(-360, 360));
    cmd->add_option("--altitude", o.altitude, "View direction above the horizontal, degrees (negative looks down)")
        ->check(number_between(-90, 90));
    cmd->add_option("--fov", o.fov, "Horizontal field of view, degrees")->check(number_between(0.001, 178.999));
    cmd->add_option("--target", o.target,
                    std::string("A place to look at ") + place +
                        ": aimed at from --position, or seen from --distance along --azimuth/--altitude");
    cmd->add_option("--distance", o.distance, "Metres from the camera to --target (default: half the DEM's extent)")
        ->check(number_between(1e-3, 1e8));
}

namespace {
// The camera options over the scene's camera (after --map's plan view).
void apply_camera_overrides(const SceneOverrides& o, Scene& scene) {
    SceneCamera& c = scene.camera;
    if (!scene.mesh.empty()) {
        const std::pair<const char*, bool> terrain_only[] = {{"--position", o.position.has_value()},
                                                             {"--elevation", o.elevation.has_value()},
                                                             {"--target", o.target.has_value()},
                                                             {"--distance", o.distance.has_value()}};
        for (const auto& [name, given] : terrain_only)
            if (given)
                throw Error("cli", o.input, std::string(name) +
                                                " applies to terrain scenes only (a mesh's camera is set by [camera] eye, "
                                                "target and up)");
    }
    if (o.position) c.position = o.position;
    if (o.elevation) c.elevation = o.elevation;
    if (o.azimuth) c.azimuth = o.azimuth;
    if (o.altitude) c.altitude = o.altitude;
    if (o.fov) c.fov = *o.fov;
    if (o.target) c.target = o.target;
    if (o.distance) c.distance = o.distance;
}
}  // namespace

Scene load_scene_with_overrides(const SceneOverrides& o) {
    Scene scene = load_scene(o.input);
    if (o.width != SceneOverrides::unset) scene.camera.width = o.width;
    if (o.height != SceneOverrides::unset) scene.camera.height = o.height;
    if (o.seed >= 0) scene.seed = std::uint64_t(o.seed);
    if (o.vertical_exaggeration == "auto") scene.exaggeration_auto = true;
    else if (!o.vertical_exaggeration.empty())
        scene.vertical_exaggeration = std::stod(o.vertical_exaggeration), scene.exaggeration_auto = false;
    if (o.map) {
        scene.camera.projection = Projection::orthographic;
        scene.camera.azimuth = 0.0, scene.camera.altitude = -90.0;
        scene.camera.position.reset(), scene.camera.elevation.reset();
        scene.camera.target.reset(), scene.camera.distance.reset();
    }
    apply_camera_overrides(o, scene);
    if (!o.scale.empty()) scene.map_scale = parse_map_scale(o.scale);
    if (o.sea_level) scene.sea_level = o.sea_level;
    if (!o.style.empty()) scene.style = o.style;
    validate_scene(scene);
    check_scene_memory(scene, o.max_memory);
    return scene;
}

}  // namespace penink
