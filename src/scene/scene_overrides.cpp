#include "scene/scene_overrides.hpp"

#include "core/error.hpp"
#include "scene/map_furniture.hpp"
#include "scene/map_scale.hpp"
#include "scene/scene_memory.hpp"

namespace penink {

namespace {
// The camera options over the scene's camera (after --map's plan view).
void apply_camera_overrides(const SceneOverrides& o, Scene& scene) {
    SceneCamera& c = scene.view.camera;
    if (!scene.source.mesh.empty()) {
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
    Scene scene = load_scene(o.input, o.style);
    if (o.width != SceneOverrides::unset) scene.view.camera.width = o.width;
    if (o.height != SceneOverrides::unset) scene.view.camera.height = o.height;
    if (o.seed >= 0) scene.style.seed = std::uint64_t(o.seed);
    if (o.vertical_exaggeration == "auto") scene.terrain.exaggeration_auto = true;
    else if (!o.vertical_exaggeration.empty())
        scene.terrain.vertical_exaggeration = std::stod(o.vertical_exaggeration), scene.terrain.exaggeration_auto = false;
    if (o.map) {
        scene.view.camera.projection = Projection::orthographic;
        scene.view.camera.azimuth = 0.0, scene.view.camera.altitude = -90.0;
        scene.view.camera.position.reset(), scene.view.camera.elevation.reset();
        scene.view.camera.target.reset(), scene.view.camera.distance.reset();
    }
    apply_camera_overrides(o, scene);
    if (!o.scale.empty()) scene.view.map_scale = parse_map_scale(o.scale);
    if (o.sea_level) scene.terrain.sea_level = o.sea_level;
    if (o.no_furniture) scene.view.furniture.neatline = scene.view.furniture.scale_bar = scene.view.furniture.north_arrow = false;
    if (o.no_furniture) scene.view.furniture.grid = MapGrid::none, scene.view.furniture.title.clear();
    if (o.grid) scene.view.furniture.grid = map_grid_named(*o.grid);  // CLI11 checked the name
    if (o.title) scene.view.furniture.title = *o.title;
    if (!o.cache_dir.empty()) scene.terrain.cache_dir = o.cache_dir;
    scene.terrain.max_memory = o.max_memory;
    validate_scene(scene);
    check_scene_memory(scene, o.max_memory);
    return scene;
}

}  // namespace penink
