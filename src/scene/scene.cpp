#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "core/closest_name.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/toml_file.hpp"
#include "drainage/drainage_build.hpp"
#include "scene/hachure_lines.hpp"
#include "scene/map_furniture.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;

bool has_key(const toml::value& t, const char* key) { return t.is_table() && t.contains(key); }

// The keys each table of a scene file takes (terrain and mesh scenes alike: scene/mesh_scene.hpp
// reads the mesh ones); [style] is the style parser's to check, [textures] material a table of
// free material names.
struct KnownTable {
    const char* name;
    std::vector<std::string> keys;
};

std::vector<std::string> map_keys() {
    std::vector<std::string> keys = map_furniture_keys();
    keys.insert(keys.begin(), "scale");
    return keys;
}

const std::vector<KnownTable>& known_tables() {
    static const std::vector<std::string> crease = {"slope_weight", "illumination_weight", "flow_weight", "min_score",
                                                    "distance_attenuation", "spacing_px", "normalisation", "enabled"};
    static const std::vector<KnownTable> tables = {
        {"terrain", {"dem", "vertical_exaggeration", "sea_level"}},
        {"camera", {"projection", "position", "elevation", "azimuth", "altitude", "target", "distance", "fov", "width",
                    "height", "eye", "up"}},
        {"map", map_keys()},
        {"light", {"azimuth", "altitude", "direction"}},
        {"tessellation", {"target_edge_px", "max_level", "cull"}},
        {"surface", {"tolerance_px", "min_radius_px"}},
        {"silhouettes", {"min_gap", "separate_passes", "method"}},
        {"creases", crease},
        {"ridges", crease},
        {"hachures", hachure_keys()},
        {"drainage", {"routing"}},
        {"cache", {"dir"}},
        {"style", {}},
        {"mesh", {"file", "up", "subdivide"}},
        {"pels", {"enabled", "threshold", "smoothing", "normal_filter", "line_strength"}},
        {"features", {"enabled", "crease_angle"}},
        {"textures", {"enabled", "threshold", "confidence", "scale", "library", "material"}},
    };
    return tables;
}

// Every key and table of the file is one the scene reads, else "unknown key K in [T]; did you
// mean N?" / "unknown table [T]; did you mean [N]?" (keys in file order).
void check_known_keys(const toml::value& root, const std::string& file) {
    std::vector<std::string> table_names, root_keys = {"seed"};
    for (const KnownTable& t : known_tables()) table_names.emplace_back(t.name);
    for (const auto& entry : root.as_table()) {
        const std::string& key = entry.first;
        const toml::value& value = entry.second;
        const auto t = std::find_if(known_tables().begin(), known_tables().end(),
                                    [&key](const KnownTable& k) { return key == k.name; });
        if (t == known_tables().end()) {
            if (value.is_table()) {
                const std::string near = closest_name(key, table_names);
                throw Error("scene", file, "unknown table [" + key + "]" + (near.empty() ? "" : "; did you mean [" + near + "]?"));
            }
            if (key != "seed") {
                std::vector<std::string> all = root_keys;
                all.insert(all.end(), table_names.begin(), table_names.end());
                throw Error("scene", file, "unknown key " + key + did_you_mean(key, all));
            }
            continue;
        }
        if (!value.is_table()) throw Error("scene", file, "[" + key + "] must be a table");
        if (t->keys.empty()) continue;  // [style]: the style parser's
        for (const auto& [k, v] : value.as_table())
            if (std::find(t->keys.begin(), t->keys.end(), k) == t->keys.end())
                throw Error("scene", file, "unknown key " + k + " in [" + key + "]" + did_you_mean(k, t->keys));
    }
}

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
    if (!std::isfinite(out)) throw Error("scene", file, "[" + section + "] " + key + ": expected a finite number");
}

// An integer key within [lo, hi] (read as 64 bits: no wrap), else "[S] K: must be an integer
// between LO and HI (got V)".
void read_int(const toml::value& table, const char* key, int& out, const std::string& file, const std::string& section,
              int lo, int hi) {
    if (!has_key(table, key)) return;
    const toml::value& v = table.at(key);
    const std::string range = "must be an integer between " + std::to_string(lo) + " and " + std::to_string(hi);
    if (!v.is_integer()) throw Error("scene", file, "[" + section + "] " + key + ": " + range);
    const std::int64_t x = v.as_integer();
    if (x < lo || x > hi)
        throw Error("scene", file, "[" + section + "] " + key + ": " + range + " (got " + std::to_string(x) + ")");
    out = int(x);
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
    if (has_key(t, "normalisation")) {
        std::string name;
        read_key(t, "normalisation", name, file, section);
        const auto n = score_normalisation_named(name);
        if (!n)
            throw Error("scene", file, "[" + std::string(section) + "] normalisation must be \"thirds\", \"paper\" or \"rank\" (got \"" +
                                           name + "\")");
        p.normalisation = *n;
    }
    read_key(t, "enabled", p.enabled, file, section);
}

// A [camera] key of the other kind of scene is an error naming it: position, elevation, distance
// and a place as target are a terrain's; eye, up and an [x, y, z] target a mesh's.
void check_camera_kind(const toml::value& t, bool mesh, const std::string& file) {
    const bool place_target = has_key(t, "target") && t.at("target").is_string();
    const std::string terrain_only = " applies to terrain scenes only (a mesh's camera takes eye, target = [x, y, z] and up)";
    const std::string mesh_only = " applies to mesh scenes only (a terrain's camera takes position, elevation, azimuth, "
                                  "altitude, target = \"PLACE\" and distance)";
    for (const char* key : {"position", "elevation", "distance"})
        if (mesh && has_key(t, key)) throw Error("scene", file, std::string("[camera] ") + key + terrain_only);
    for (const char* key : {"eye", "up"})
        if (!mesh && has_key(t, key)) throw Error("scene", file, std::string("[camera] ") + key + mesh_only);
    if (mesh && place_target) throw Error("scene", file, "[camera] target as a place" + terrain_only);
    if (!mesh && has_key(t, "target") && !place_target)
        throw Error("scene", file, "[camera] target: expected a place (\"LON,LAT\", \"EASTING NORTHING ZONE\" or \"X Y\")");
}

void read_camera(const toml::value& root, SceneCamera& cam, const std::string& file, bool mesh) {
    if (!has_key(root, "camera")) return;
    const toml::value& t = root.at("camera");
    check_camera_kind(t, mesh, file);
    if (has_key(t, "position")) {
        std::string pos;
        read_key(t, "position", pos, file, "camera");
        cam.position = pos;
    }
    if (!mesh && has_key(t, "target")) {
        std::string place;
        read_key(t, "target", place, file, "camera");
        cam.target = place;
    }
    read_optional(t, "distance", cam.distance, file, "camera");
    if (has_key(t, "projection")) {
        std::string name;
        read_key(t, "projection", name, file, "camera");
        const auto named = projection_named(name);
        if (!named)
            throw Error("scene", file, "[camera] projection must be \"perspective\" or \"orthographic\" (got \"" + name + "\")");
        cam.projection = *named;
    }
    read_optional(t, "elevation", cam.elevation, file, "camera");
    read_optional(t, "azimuth", cam.azimuth, file, "camera");
    read_optional(t, "altitude", cam.altitude, file, "camera");
    read_number(t, "fov", cam.fov, file, "camera");
    // 0 and below pass here: validate_scene says "image size must be positive" for any source
    read_int(t, "width", cam.width, file, "camera", std::numeric_limits<int>::min() + 1, max_image_side);
    read_int(t, "height", cam.height, file, "camera", std::numeric_limits<int>::min() + 1, max_image_side);
}

Scene parse_scene_file(const std::string& path) {
    Scene s;
    s.file = path;
    const toml::value root = read_toml_file("scene", path, "scene file");
    s.table = root;
    check_known_keys(root, path);
    if (has_key(root, "mesh")) {
        if (!has_key(root.at("mesh"), "file")) throw Error("scene", path, "missing [mesh] file");
        read_key(root.at("mesh"), "file", s.mesh, path, "mesh");
        check_local_path("input", s.mesh);  // a NUL byte, a URL or /vs path: before it is resolved
        if (fs::path(s.mesh).is_relative()) s.mesh = (fs::path(path).parent_path() / s.mesh).lexically_normal().string();
    } else if (!has_key(root, "terrain") || !has_key(root.at("terrain"), "dem")) {
        throw Error("scene", path, "missing [terrain] dem (or [mesh] file)");
    }
    const toml::value terrain = has_key(root, "terrain") ? root.at("terrain") : toml::value(toml::table{});
    read_key(terrain, "dem", s.dem, path, "terrain");
    check_local_path("input", s.dem);  // a NUL byte, a URL or /vs path: before it is resolved
    if (!s.dem.empty() && fs::path(s.dem).is_relative())
        s.dem = (fs::path(path).parent_path() / s.dem).lexically_normal().string();
    if (has_key(terrain, "vertical_exaggeration")) {
        const toml::value& v = terrain.at("vertical_exaggeration");
        if (v.is_string() && v.as_string().str == "auto") {
            s.exaggeration_auto = true;
        } else if (v.is_string()) {
            throw Error("scene", path, "[terrain] vertical_exaggeration: expected a number or \"auto\"");
        } else {
            read_number(terrain, "vertical_exaggeration", s.vertical_exaggeration, path, "terrain");
            s.exaggeration_auto = false;
        }
    }
    if (has_key(terrain, "sea_level")) {
        double sea = 0.0;
        read_number(terrain, "sea_level", sea, path, "terrain");
        s.sea_level = sea;
    }
    read_camera(root, s.camera, path, !s.mesh.empty());
    if (has_key(root, "map")) {
        read_number(root.at("map"), "scale", s.map_scale, path, "map");
        s.furniture = read_map_furniture(root.at("map"), path);
    }
    if (has_key(root, "light")) {
        read_number(root.at("light"), "azimuth", s.light.azimuth, path, "light");
        read_number(root.at("light"), "altitude", s.light.altitude, path, "light");
    }
    if (has_key(root, "tessellation")) {
        double target = s.tess_target_edge_px;
        read_number(root.at("tessellation"), "target_edge_px", target, path, "tessellation");
        s.tess_target_edge_px = float(target);
        read_int(root.at("tessellation"), "max_level", s.tess_max_level, path, "tessellation", 1, 64);
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
            throw Error("scene", path, "[silhouettes] method must be \"toward-away\", \"adjacency\", \"edge-walk\" or \"object-space\" (got \"" +
                                           method + "\")");
        s.silhouette_method = *named;
    }
    read_crease(root, "creases", s.creases, path);
    read_crease(root, "ridges", s.ridges, path);
    read_hachures(root, s.hachures, path);
    if (has_key(root, "drainage")) read_key(root.at("drainage"), "routing", s.drainage_routing, path, "drainage");
    if (has_key(root, "cache")) {
        read_key(root.at("cache"), "dir", s.cache_dir, path, "cache");
        check_local_path("scene", s.cache_dir);
        if (!s.cache_dir.empty() && fs::path(s.cache_dir).is_relative())
            s.cache_dir = (fs::path(path).parent_path() / s.cache_dir).lexically_normal().string();
    }
    if (has_key(root, "style")) {
        s.style_overrides = root.at("style");
        read_key(root.at("style"), "name", s.style, path, "style");
    }
    if (has_key(root, "seed")) {
        if (!root.at("seed").is_integer() || root.at("seed").as_integer() < 0)
            throw Error("scene", path, "seed: must be an integer >= 0");
        s.seed = std::uint64_t(root.at("seed").as_integer());
    }
    return s;
}

std::string short_number(double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%g", v);
    return s;
}

// "NAME must be between LO and HI UNIT (got V)" unless lo <= v <= hi.
void check_range(const std::string& file, const std::string& name, double v, double lo, double hi,
                 const std::string& unit = "") {
    if (v >= lo && v <= hi) return;
    throw Error("scene", file, name + " must be between " + short_number(lo) + " and " + short_number(hi) + unit +
                                   " (got " + short_number(v) + ")");
}

void check_range(const std::string& file, const std::string& name, const std::optional<double>& v, double lo,
                 double hi, const std::string& unit) {
    if (v) check_range(file, name, *v, lo, hi, unit);
}

}  // namespace

std::optional<SilhouetteMethod> silhouette_method_named(const std::string& name) {
    for (SilhouetteMethod m : {SilhouetteMethod::toward_away, SilhouetteMethod::adjacency, SilhouetteMethod::edge_walk,
                               SilhouetteMethod::object_space})
        if (name == silhouette_method_name(m)) return m;
    return std::nullopt;
}

const char* silhouette_method_name(SilhouetteMethod method) {
    switch (method) {
        case SilhouetteMethod::adjacency: return "adjacency";
        case SilhouetteMethod::edge_walk: return "edge-walk";
        case SilhouetteMethod::object_space: return "object-space";
        case SilhouetteMethod::toward_away: break;
    }
    return "toward-away";
}

Scene load_scene(const std::string& input) {
    check_local_path("input", input);
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
    if (!(s.vertical_exaggeration > 0.0 && s.vertical_exaggeration <= max_vertical_exaggeration))
        throw Error("scene", f, "vertical exaggeration must be > 0 and at most 1000 (got " +
                                    short_number(s.vertical_exaggeration) + ")");
    check_range(f, "[camera] altitude", s.camera.altitude, -90.0, 90.0, " degrees");
    check_range(f, "[camera] azimuth", s.camera.azimuth, -360.0, 360.0, " degrees");
    check_range(f, "[camera] elevation", s.camera.elevation, -1e7, 1e7, " metres");
    check_range(f, "[terrain] sea_level", s.sea_level, -1e7, 1e7, " metres");
    check_range(f, "[light] altitude", s.light.altitude, 0.0, 90.0, " degrees");  // a sun: above the horizon
    check_range(f, "[light] azimuth", s.light.azimuth, -360.0, 360.0, " degrees");
    for (const auto& [name, p] : {std::pair<const char*, const CreaseParams*>{"creases", &s.creases}, {"ridges", &s.ridges}}) {
        const std::string t = std::string("[") + name + "] ";
        check_range(f, t + "slope_weight", p->slope_weight, 0.0, 1000.0);
        check_range(f, t + "illumination_weight", p->illumination_weight, 0.0, 1000.0);
        check_range(f, t + "flow_weight", p->flow_weight, 0.0, 1000.0);
        check_range(f, t + "min_score", p->min_score, -1000.0, 1000.0);
        check_range(f, t + "distance_attenuation", p->distance_attenuation, 0.0, 1000.0);
        check_range(f, t + "spacing_px", p->spacing_px, 0.0, 1000.0);
    }
    validate_hachures(s.hachures, f);
    check_range(f, "[silhouettes] min_gap", double(s.silhouette_min_gap), 0.0, 1000.0);
    if (s.tess_max_level < 1 || s.tess_max_level > 64)
        throw Error("scene", f, "tessellation max_level must be between 1 and 64");
    if (!(s.surface_tolerance_px >= 0.0f && s.surface_tolerance_px <= 1000.0f))
        throw Error("scene", f, "[surface] tolerance_px must be between 0 and 1000");
    if (!(s.surface_min_radius_px >= 0.0f && s.surface_min_radius_px <= 1000.0f))
        throw Error("scene", f, "[surface] min_radius_px must be between 0 and 1000");
    if (!(s.tess_target_edge_px > 0.0f && s.tess_target_edge_px <= 1000.0f))
        throw Error("scene", f, "tessellation target_edge_px must be > 0 and at most 1000");
    if (!drainage_routing_named(s.drainage_routing))
        throw Error("scene", f, "[drainage] routing must be \"priority-flood\" or \"least-cost\" (got \"" +
                                    s.drainage_routing + "\")");
    const bool ortho = s.camera.projection == Projection::orthographic;
    if (!ortho && s.camera.position.has_value() != s.camera.elevation.has_value())
        throw Error("scene", f, "camera position and elevation go together (give both or neither)");
    const SceneCamera& c = s.camera;
    if (c.target && c.position && (c.azimuth || c.altitude))
        throw Error("scene", f, "camera azimuth and altitude follow from position and target: give one or the other");
    if (c.target && c.position && ortho)
        throw Error("scene", f, "an orthographic view is centred on its position or its target, not both");
    if (c.distance && !c.target) throw Error("scene", f, "camera distance goes with a target (the place looked at)");
    if (c.distance && c.position) throw Error("scene", f, "camera distance and position both place the camera: give one");
    check_range(f, "[camera] distance", c.distance, 1e-3, 1e8, " metres");
    if (s.map_scale != 0.0) {
        check_range(f, "[map] scale", s.map_scale, 1.0, 1e9);
        if (!ortho)
            throw Error("scene", f, "a map scale needs an orthographic view ([camera] projection = \"orthographic\", or --map)");
    }
}

std::optional<Projection> projection_named(const std::string& name) {
    for (Projection p : {Projection::perspective, Projection::orthographic})
        if (name == projection_name(p)) return p;
    return std::nullopt;
}

const char* projection_name(Projection projection) {
    return projection == Projection::orthographic ? "orthographic" : "perspective";
}

}  // namespace penink
