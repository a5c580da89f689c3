#include "scene/scene.hpp"

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "drainage/drainage_build.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;

bool has_key(const toml::value& t, const char* key) { return t.is_table() && t.contains(key); }

template <typename T>
void read_key(const toml::value& table, const char* key, T& out, const std::string& file,
              const std::string& section) {
    if (!has_key(table, key)) return;
    try {
        out = toml::get<T>(table.at(key));
    } catch (const std::exception&) {
        throw Error("scene", file, "[" + section + "] " + key + ": wrong type");
    }
}

void read_number(const toml::value& table, const char* key, double& out, const std::string& file,
                 const std::string& section) {
    if (!has_key(table, key)) return;
    const toml::value& v = table.at(key);
    if (v.is_integer()) out = double(v.as_integer());
    else if (v.is_floating()) out = v.as_floating();
    else throw Error("scene", file, "[" + section + "] " + key + ": expected a number");
}

void read_optional(const toml::value& table, const char* key, std::optional<double>& out,
                   const std::string& file, const std::string& section) {
    if (!has_key(table, key)) return;
    double v = 0.0;
    read_number(table, key, v, file, section);
    out = v;
}

void read_crease(const toml::value& root, const char* section, CreaseParams& p, const std::string& file) {
    if (!has_key(root, section)) return;
    const toml::value& t = root.at(section);
    read_number(t, "slope_weight", p.slope_weight, file, section);
    read_number(t, "illumination_weight", p.illumination_weight, file, section);
    read_number(t, "flow_weight", p.flow_weight, file, section);
    read_number(t, "min_score", p.min_score, file, section);
    read_number(t, "distance_attenuation", p.distance_attenuation, file, section);
    read_number(t, "spacing_px", p.spacing_px, file, section);
    read_key(t, "enabled", p.enabled, file, section);
}

void read_camera(const toml::value& root, SceneCamera& cam, const std::string& file) {
    if (!has_key(root, "camera")) return;
    const toml::value& t = root.at("camera");
    if (has_key(t, "position")) {
        std::string pos;
        read_key(t, "position", pos, file, "camera");
        cam.position = pos;
    }
    read_optional(t, "elevation", cam.elevation, file, "camera");
    read_optional(t, "azimuth", cam.azimuth, file, "camera");
    read_optional(t, "altitude", cam.altitude, file, "camera");
    read_number(t, "fov", cam.fov, file, "camera");
    read_key(t, "width", cam.width, file, "camera");
    read_key(t, "height", cam.height, file, "camera");
}

Scene parse_scene_file(const std::string& path) {
    Scene s;
    s.file = path;
    toml::value root;
    try {
        root = toml::parse(path);
    } catch (const std::exception& e) {
        std::string what = e.what();
        const auto nl = what.find('\n');
        throw Error("scene", path, "not a valid TOML scene (" + what.substr(0, nl) + ")");
    }
    s.table = root;
    if (has_key(root, "mesh")) {
        if (!has_key(root.at("mesh"), "file")) throw Error("scene", path, "missing [mesh] file");
        read_key(root.at("mesh"), "file", s.mesh, path, "mesh");
        if (fs::path(s.mesh).is_relative()) s.mesh = (fs::path(path).parent_path() / s.mesh).lexically_normal().string();
    } else if (!has_key(root, "terrain") || !has_key(root.at("terrain"), "dem")) {
        throw Error("scene", path, "missing [terrain] dem (or [mesh] file)");
    }
    const toml::value terrain = has_key(root, "terrain") ? root.at("terrain") : toml::value(toml::table{});
    read_key(terrain, "dem", s.dem, path, "terrain");
    if (!s.dem.empty() && fs::path(s.dem).is_relative())
        s.dem = (fs::path(path).parent_path() / s.dem).lexically_normal().string();
    read_number(terrain, "vertical_exaggeration", s.vertical_exaggeration, path, "terrain");
    read_camera(root, s.camera, path);
    if (has_key(root, "light")) {
        read_number(root.at("light"), "azimuth", s.light.azimuth, path, "light");
        read_number(root.at("light"), "altitude", s.light.altitude, path, "light");
    }
    if (has_key(root, "tessellation")) {
        double target = s.tess_target_edge_px;
        read_number(root.at("tessellation"), "target_edge_px", target, path, "tessellation");
        s.tess_target_edge_px = float(target);
        read_key(root.at("tessellation"), "max_level", s.tess_max_level, path, "tessellation");
        read_key(root.at("tessellation"), "cull", s.cull_patches, path, "tessellation");
    }
    if (has_key(root, "surface")) {
        double tolerance = s.surface_tolerance_px, min_radius = s.surface_min_radius_px;
        read_number(root.at("surface"), "tolerance_px", tolerance, path, "surface");
        read_number(root.at("surface"), "min_radius_px", min_radius, path, "surface");
        s.surface_tolerance_px = float(tolerance), s.surface_min_radius_px = float(min_radius);
    }
    if (has_key(root, "silhouettes")) {
        double gap = s.silhouette_min_gap;
        read_number(root.at("silhouettes"), "min_gap", gap, path, "silhouettes");
        s.silhouette_min_gap = float(gap);
        read_key(root.at("silhouettes"), "separate_passes", s.separate_passes, path, "silhouettes");
        std::string method = silhouette_method_name(s.silhouette_method);
        read_key(root.at("silhouettes"), "method", method, path, "silhouettes");
        const auto named = silhouette_method_named(method);
        if (!named)
            throw Error("scene", path, "[silhouettes] method must be \"toward-away\", \"adjacency\" or \"object-space\" (got \"" +
                                           method + "\")");
        s.silhouette_method = *named;
    }
    read_crease(root, "creases", s.creases, path);
    read_crease(root, "ridges", s.ridges, path);
    if (has_key(root, "drainage")) read_key(root.at("drainage"), "routing", s.drainage_routing, path, "drainage");
    if (has_key(root, "style")) {
        s.style_overrides = root.at("style");
        read_key(root.at("style"), "name", s.style, path, "style");
    }
    if (has_key(root, "seed")) {
        std::int64_t seed = 0;
        read_key(root, "seed", seed, path, "seed");
        s.seed = std::uint64_t(seed);
    }
    return s;
}

}  // namespace

std::optional<SilhouetteMethod> silhouette_method_named(const std::string& name) {
    for (SilhouetteMethod m : {SilhouetteMethod::toward_away, SilhouetteMethod::adjacency, SilhouetteMethod::object_space})
        if (name == silhouette_method_name(m)) return m;
    return std::nullopt;
}

const char* silhouette_method_name(SilhouetteMethod method) {
    switch (method) {
        case SilhouetteMethod::adjacency: return "adjacency";
        case SilhouetteMethod::object_space: return "object-space";
        case SilhouetteMethod::toward_away: break;
    }
    return "toward-away";
}

Scene load_scene(const std::string& input) {
    const bool is_scene = fs::path(input).extension() == ".toml";
    if (is_scene && !fs::exists(input)) throw Error("scene", input, "no such file");
    if (is_scene) return parse_scene_file(input);
    Scene s;
    s.dem = input;
    return s;
}

void validate_scene(const Scene& s) {
    const std::string& f = s.file.empty() ? s.dem : s.file;
    if (s.camera.width <= 0 || s.camera.height <= 0)
        throw Error("scene", f, "image size must be positive (got " + std::to_string(s.camera.width) +
                                    "x" + std::to_string(s.camera.height) + ")");
    if (s.camera.width > max_image_side || s.camera.height > max_image_side)
        throw Error("scene", f, "image size is too large (at most " + std::to_string(max_image_side) + " pixels a side)");
    if (!(s.camera.fov > 0.0 && s.camera.fov < 179.0))
        throw Error("scene", f, "camera fov must be between 0 and 179 degrees");
    if (!(s.vertical_exaggeration > 0.0))
        throw Error("scene", f, "vertical exaggeration must be > 0");
    if (s.tess_max_level < 1 || s.tess_max_level > 64)
        throw Error("scene", f, "tessellation max_level must be between 1 and 64");
    if (!(s.surface_tolerance_px >= 0.0f && s.surface_tolerance_px <= 1000.0f))
        throw Error("scene", f, "[surface] tolerance_px must be between 0 and 1000");
    if (!(s.surface_min_radius_px >= 0.0f && s.surface_min_radius_px <= 1000.0f))
        throw Error("scene", f, "[surface] min_radius_px must be between 0 and 1000");
    if (!(s.tess_target_edge_px > 0.0f))
        throw Error("scene", f, "tessellation target_edge_px must be > 0");
    if (!drainage_routing_named(s.drainage_routing))
        throw Error("scene", f, "[drainage] routing must be \"priority-flood\" or \"least-cost\" (got \"" +
                                    s.drainage_routing + "\")");
    if (s.camera.position.has_value() != s.camera.elevation.has_value())
        throw Error("scene", f, "camera position and elevation go together (give both or neither)");
}

}  // namespace penink
