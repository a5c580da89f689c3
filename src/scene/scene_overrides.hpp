// Command-line values that override a scene's (shared by render and batch; src/cli parses them):
// the input, style, OpenGL back-end, image size, the camera, seed, vertical exaggeration, sea
// level, map view and scale, and the scene loaded with them applied and validated.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "scene/scene.hpp"

namespace penink {

struct SceneOverrides {
    std::string input;           // DEM, mesh or scene file
    std::string style;           // name or path; "" = the scene's
    std::string gl = "osmesa";
    static constexpr int unset = -2147483647;  // (any int is a value the check must see)
    int width = unset, height = unset;
    long long seed = -1;                       // < 0: the scene's
    std::string vertical_exaggeration;         // a number or "auto"; "": the scene's
    std::optional<double> sea_level;           // --sea-level; none: the scene's
    bool map = false;                          // --map: orthographic plan view of the whole DEM
    std::string scale;                         // --scale 1:N; "": the scene's
    std::uint64_t max_memory = 0;              // --max-memory; 0: the memory available
    // A plan view's furniture ([map] keys, scene/map_furniture.hpp): --title, --grid, --no-furniture.
    std::optional<std::string> title, grid;
    bool no_furniture = false;
    std::string cache_dir;                     // --cache-dir; "": the scene's [cache] dir
    // The camera ([camera] keys of the same names, scene.hpp); none: the scene's.
    std::optional<std::string> position, target;
    std::optional<double> elevation, azimuth, altitude, fov, distance;
};

// load_scene(o.input) with the overrides applied, then validate_scene, then (a terrain) the
// memory its DEM would need checked against --max-memory (check_scene_memory). --map replaces the
// scene's camera placement (position, elevation, target, distance) by the plan view's; the camera
// options then apply over it. A camera option a mesh scene does not take (--position,
// --elevation, --target, --distance) is an error naming it (stage "cli").
Scene load_scene_with_overrides(const SceneOverrides& o);

}  // namespace penink
