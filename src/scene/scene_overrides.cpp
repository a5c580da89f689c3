#include "scene/scene_overrides.hpp"

#include "core/error.hpp"
#include "scene/map_furniture.hpp"
#include "scene/map_scale.hpp"
#include "scene/scene_memory.hpp"

namespace penink {

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
    if (o.no_furniture) scene.furniture.neatline = scene.furniture.scale_bar = scene.furniture.north_arrow = false;
    if (o.no_furniture) scene.furniture.grid = MapGrid::none, scene.furniture.title.clear();
    if (o.grid) scene.furniture.grid = map_grid_named(*o.grid);  // CLI11 checked the name
    if (o.title) scene.furniture.title = *o.title;
    if (!o.style.empty()) scene.style = o.style;
    if (!o.cache_dir.empty()) scene.cache_dir = o.cache_dir;
    validate_scene(scene);
    check_scene_memory(scene, o.max_memory);
    return scene;
}

}  // namespace penink
