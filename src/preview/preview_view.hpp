// What the preview page steers, in the scene file's own terms (scene/scene.hpp's keys), and the
// scene file it makes: the camera as a target on the ground ("x y" in the DEM's projected CRS),
// the distance to it, azimuth and altitude (orbit: azimuth and altitude; pan: the target; the
// wheel: the distance), the field of view and image size, the sun, a numeric vertical
// exaggeration, the creases' and ridges' min_score, the hachures' spacing, the style, each
// layer's visibility ([style.<layer>] visible), the seed and the sea level. Every frame the
// preview draws is loaded from scene_text (load_scene), so a saved file draws the same.
#pragma once
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace penink {

struct PreviewView {
    bool orthographic = false;
    double target_x = 0.0, target_y = 0.0;  // DEM CRS units, the point looked at
    double distance = 1000.0;               // metres from the camera to the target (perspective)
    double azimuth = 45.0, altitude = -30.0;
    double fov = 40.0;
    int width = 1000, height = 750;
    double light_azimuth = 315.0, light_altitude = 45.0;
    double vertical_exaggeration = 1.0;
    double crease_min_score = 0.12, ridge_min_score = 0.05;
    double hachure_spacing_min = 2.0, hachure_spacing_max = 12.0;  // image pixels
    std::string style = "technical";
    std::map<std::string, bool> visible;  // layer name -> drawn; a layer not named is drawn
    std::uint64_t seed = 1;
    std::optional<double> sea_level;
    double map_scale = 0.0;  // [map] scale, orthographic views; 0: none
};

// The view as the page reads it (numbers, the style, the layers).
nlohmann::json view_json(const PreviewView& view);

// `view` with the members `j` holds changed; a member of the wrong type or out of the scene's
// ranges (validate_scene's, the [hachures] checks') throws std::invalid_argument naming it.
// Image sizes are held to 16..max_image_side, distances to (0, 1e8].
PreviewView view_from_json(const nlohmann::json& j, const PreviewView& view);

// The scene file of `view`: `base` (a scene file's TOML text, "" for none; its [camera] position,
// elevation and distance and [terrain] keys replaced) with the view's keys set, `dem` as
// [terrain] dem. Keys sorted, tables after the keys, numbers written so that they read back
// exactly. Throws Error("scene", "", "invalid TOML: ...") when `base` is not TOML.
std::string scene_text(const std::string& base, const std::string& dem, const PreviewView& view);

// `base` (a scene file's TOML text, "" for none) with [cache] dir set to `dir` (an absolute path),
// so that the frames and the file saved keep the cache folder the preview was started with.
std::string with_cache_dir(const std::string& base, const std::string& dir);

// The layers `base` (a scene file's TOML text) draws or not: its [style.<layer>] visible keys.
std::map<std::string, bool> scene_visibility(const std::string& base);

// A number as TOML writes it, the shortest text that reads back as the same double.
std::string toml_number(double value);

}  // namespace penink
