// The scene file's reader (scene.hpp: load_scene): every table and key checked against the ones
// the scene reads, the values read into the scene's parts (a mesh scene's keys into MeshSettings),
// and the style resolved with the file's [style] table over it. The only reader of a scene's
// TOML (core/toml_file.hpp); validate_scene (scene.cpp) holds the values to their ranges.
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "core/closest_name.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/toml_file.hpp"
#include "scene/hachure_lines.hpp"
#include "scene/map_furniture.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;

bool has_key(const toml::value& t, const char* key) { return t.is_table() && t.contains(key); }

// The keys each table of a scene file takes (terrain and mesh scenes alike: read_mesh_settings
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

// [hachures]: each key of hachure_keys() into p; "[hachures] KEY: ..." on a wrong type or name.
void read_hachure_value(const toml::value& t, const char* key, double& out, const std::string& file) {
    if (!t.contains(key)) return;
    const toml::value& v = t.at(key);
    if (v.is_integer()) out = double(v.as_integer());
    else if (v.is_floating()) out = v.as_floating();
    else throw Error("scene", file, std::string("[hachures] ") + key + ": expected a number");
    if (!std::isfinite(out)) throw Error("scene", file, std::string("[hachures] ") + key + ": expected a finite number");
}

void read_hachures(const toml::value& root, HachureParams& p, const std::string& file) {
    if (!root.is_table() || !root.contains("hachures")) return;
    const toml::value& t = root.at("hachures");
    if (t.contains("enabled")) {
        if (!t.at("enabled").is_boolean()) throw Error("scene", file, "[hachures] enabled: must be true or false");
        p.enabled = t.at("enabled").as_boolean();
    }
    if (t.contains("tone")) {
        const toml::value& v = t.at("tone");
        if (!v.is_string() || !hachure_tone_named(v.as_string().str, p.tone))
            throw Error("scene", file, "[hachures] tone must be \"light\", \"slope\" or \"blend\"" +
                                           (v.is_string() ? " (got \"" + v.as_string().str + "\")" : std::string()));
    }
    for (const std::string& key : hachure_keys())  // the numbers, in the keys' order
        if (double* value = hachure_number(p, key)) read_hachure_value(t, key.c_str(), *value, file);
}

// [map] furniture keys (map_furniture_keys); "[map] KEY: ..." on a wrong type or name.
bool read_map_bool(const toml::value& t, const char* key, bool fallback, const std::string& file) {
    if (!t.contains(key)) return fallback;
    if (!t.at(key).is_boolean()) throw Error("scene", file, std::string("[map] ") + key + ": expected true or false");
    return t.at(key).as_boolean();
}

std::string read_map_string(const toml::value& t, const char* key, const std::string& fallback, const std::string& file) {
    if (!t.contains(key)) return fallback;
    if (!t.at(key).is_string()) throw Error("scene", file, std::string("[map] ") + key + ": expected a string");
    return t.at(key).as_string().str;
}

MapFurnitureOptions read_map_furniture(const toml::value& map, const std::string& file) {
    MapFurnitureOptions o;
    if (!map.is_table()) return o;
    const bool on = read_map_bool(map, "furniture", true, file);
    o.neatline = read_map_bool(map, "neatline", on, file);
    o.scale_bar = read_map_bool(map, "scale_bar", on, file);
    o.north_arrow = read_map_bool(map, "north_arrow", on, file);
    try {
        o.grid = map_grid_named(read_map_string(map, "grid", "none", file));
    } catch (const std::invalid_argument& e) {
        throw Error("scene", file, std::string("[map] ") + e.what());
    }
    o.title = read_map_string(map, "title", "", file);
    if (o.title.size() > 1000) throw Error("scene", file, "[map] title: at most 1000 bytes");
    const std::string units = read_map_string(map, "units", "metric", file);
    if (units != "metric" && units != "imperial")
        throw Error("scene", file, "[map] units: must be \"metric\" or \"imperial\" (got \"" + units + "\")");
    o.imperial = units == "imperial";
    return o;
}

// A mesh scene's keys (MeshSettings), "[TABLE] KEY: ..." on a bad one.
struct MeshKeys {
    const toml::value& root;
    const std::string& file;

    const toml::value* section(const char* name) const {
        return root.is_table() && root.contains(name) ? &root.at(name) : nullptr;
    }
    static bool has(const toml::value* t, const char* key) { return t && t->is_table() && t->contains(key); }
    [[noreturn]] void bad(const std::string& sec, const std::string& key, const std::string& what) const {
        throw Error("scene", file, "[" + sec + "] " + key + ": " + what);
    }
    double number(const toml::value& v, const std::string& sec, const std::string& key) const {
        if (v.is_integer()) return double(v.as_integer());
        if (v.is_floating() && std::isfinite(v.as_floating())) return v.as_floating();
        bad(sec, key, v.is_floating() ? "expected a finite number" : "expected a number");
    }
    void read_float(const char* sec, const char* key, float& out) const {
        const toml::value* t = section(sec);
        if (has(t, key)) out = float(number(t->at(key), sec, key));
    }
    void read_bool(const char* sec, const char* key, bool& out) const {
        const toml::value* t = section(sec);
        if (!has(t, key)) return;
        if (!t->at(key).is_boolean()) bad(sec, key, "expected true or false");
        out = t->at(key).as_boolean();
    }
    std::string read_string(const char* sec, const char* key, std::string fallback) const {
        const toml::value* t = section(sec);
        if (!has(t, key)) return fallback;
        if (!t->at(key).is_string()) bad(sec, key, "expected a string");
        return t->at(key).as_string().str;
    }
    std::optional<glm::dvec3> read_vec3(const char* sec, const char* key) const {
        const toml::value* t = section(sec);
        if (!has(t, key)) return std::nullopt;
        const toml::value& v = t->at(key);
        if (!v.is_array() || v.as_array().size() != 3) bad(sec, key, "expected 3 numbers");
        glm::dvec3 out;
        for (int i = 0; i < 3; ++i) {
            const toml::value& c = v.as_array()[i];
            if (!c.is_integer() && !c.is_floating()) bad(sec, key, "expected 3 numbers");
            out[i] = number(c, sec, key);
        }
        return out;
    }
    void read_materials(MeshSettings& ms) const {
        const toml::value* t = section("textures");
        if (!has(t, "material")) return;
        const toml::value& m = t->at("material");
        if (!m.is_table()) bad("textures", "material", "expected material.NAME = \"texture\"");
        for (const auto& [name, v] : m.as_table()) {
            if (!v.is_string()) bad("textures", "material." + name, "expected a texture name");
            ms.materials[name] = v.as_string().str;
        }
    }
    void check_ranges(const MeshSettings& ms) const {
        if (!(ms.pel_threshold >= 0.0f)) bad("pels", "threshold", "must be >= 0");
        if (ms.smoothing < 0 || ms.smoothing > 1000) bad("pels", "smoothing", "must be between 0 and 1000");
        if (!(ms.normal_filter >= 0.0f && ms.normal_filter <= 20.0f))
            bad("pels", "normal_filter", "must be between 0 and 20 (mean edge lengths)");
        if (!(ms.line_strength >= 0.0f && ms.line_strength <= 1e6f)) bad("pels", "line_strength", "must be >= 0");
        if (!(ms.crease_angle >= 0.0f && ms.crease_angle <= 180.0f))
            bad("features", "crease_angle", "must be between 0 and 180 degrees");
        if (!(ms.texture_confidence >= 0.0f && ms.texture_confidence <= 1.0f))
            bad("textures", "confidence", "must be between 0 and 1");
        if (ms.texture_scale && !(*ms.texture_scale > 0.0f)) bad("textures", "scale", "must be > 0");
        if (ms.light && !(glm::length(*ms.light) > 0.0)) bad("light", "direction", "must not be zero");
    }
};

MeshSettings read_mesh_settings(const toml::value& root, const std::string& file) {
    const MeshKeys k{root, file};
    MeshSettings ms;
    const std::string up = k.read_string("mesh", "up", "y");
    if (up != "y" && up != "z") k.bad("mesh", "up", "use \"y\" or \"z\"");
    ms.y_up = up == "y";
    ms.up = ms.y_up ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    float subdivide = 0.0f;
    k.read_float("mesh", "subdivide", subdivide);
    if (subdivide < 0.0f || subdivide > 4.0f || subdivide != std::floor(subdivide))
        k.bad("mesh", "subdivide", "must be a whole number from 0 to 4");
    ms.subdivide = int(subdivide);
    ms.eye = k.read_vec3("camera", "eye");
    ms.target = k.read_vec3("camera", "target");
    if (auto u = k.read_vec3("camera", "up")) ms.up = *u;
    ms.light = k.read_vec3("light", "direction");
    k.read_bool("pels", "enabled", ms.pels);
    k.read_float("pels", "threshold", ms.pel_threshold);
    float smoothing = float(ms.smoothing);
    k.read_float("pels", "smoothing", smoothing);
    ms.smoothing = int(smoothing);
    k.read_float("pels", "normal_filter", ms.normal_filter);
    k.read_float("pels", "line_strength", ms.line_strength);
    k.read_bool("features", "enabled", ms.features);
    k.read_float("features", "crease_angle", ms.crease_angle);
    k.read_bool("textures", "enabled", ms.textures);
    k.read_float("textures", "threshold", ms.texture_threshold);
    k.read_float("textures", "confidence", ms.texture_confidence);
    float scale = 0.0f;
    k.read_float("textures", "scale", scale);
    if (MeshKeys::has(k.section("textures"), "scale")) ms.texture_scale = scale;
    ms.texture_library = k.read_string("textures", "library", "");
    if (!ms.texture_library.empty() && fs::path(ms.texture_library).is_relative())
        ms.texture_library = (fs::path(file).parent_path() / ms.texture_library).lexically_normal().string();
    k.read_materials(ms);
    k.check_ranges(ms);
    return ms;
}

Scene parse_scene_file(const std::string& path, const std::string& style) {
    Scene s;
    s.source.file = path;
    const toml::value root = read_toml_file("scene", path, "scene file");
    check_known_keys(root, path);
    if (has_key(root, "mesh")) {
        if (!has_key(root.at("mesh"), "file")) throw Error("scene", path, "missing [mesh] file");
        read_key(root.at("mesh"), "file", s.source.mesh, path, "mesh");
        check_local_path("input", s.source.mesh);  // a NUL byte, a URL or /vs path: before it is resolved
        if (fs::path(s.source.mesh).is_relative()) s.source.mesh = (fs::path(path).parent_path() / s.source.mesh).lexically_normal().string();
    } else if (!has_key(root, "terrain") || !has_key(root.at("terrain"), "dem")) {
        throw Error("scene", path, "missing [terrain] dem (or [mesh] file)");
    }
    const toml::value terrain = has_key(root, "terrain") ? root.at("terrain") : toml::value(toml::table{});
    read_key(terrain, "dem", s.source.dem, path, "terrain");
    check_local_path("input", s.source.dem);  // a NUL byte, a URL or /vs path: before it is resolved
    if (!s.source.dem.empty() && fs::path(s.source.dem).is_relative())
        s.source.dem = (fs::path(path).parent_path() / s.source.dem).lexically_normal().string();
    if (has_key(terrain, "vertical_exaggeration")) {
        const toml::value& v = terrain.at("vertical_exaggeration");
        if (v.is_string() && v.as_string().str == "auto") {
            s.terrain.exaggeration_auto = true;
        } else if (v.is_string()) {
            throw Error("scene", path, "[terrain] vertical_exaggeration: expected a number or \"auto\"");
        } else {
            read_number(terrain, "vertical_exaggeration", s.terrain.vertical_exaggeration, path, "terrain");
            s.terrain.exaggeration_auto = false;
        }
    }
    if (has_key(terrain, "sea_level")) {
        double sea = 0.0;
        read_number(terrain, "sea_level", sea, path, "terrain");
        s.terrain.sea_level = sea;
    }
    read_camera(root, s.view.camera, path, !s.source.mesh.empty());
    if (has_key(root, "map")) {
        read_number(root.at("map"), "scale", s.view.map_scale, path, "map");
        s.view.furniture = read_map_furniture(root.at("map"), path);
    }
    if (has_key(root, "light")) {
        read_number(root.at("light"), "azimuth", s.view.light.azimuth, path, "light");
        read_number(root.at("light"), "altitude", s.view.light.altitude, path, "light");
    }
    if (has_key(root, "tessellation")) {
        double target = s.terrain.tess_target_edge_px;
        read_number(root.at("tessellation"), "target_edge_px", target, path, "tessellation");
        s.terrain.tess_target_edge_px = float(target);
        read_int(root.at("tessellation"), "max_level", s.terrain.tess_max_level, path, "tessellation", 1, 64);
        read_key(root.at("tessellation"), "cull", s.terrain.cull_patches, path, "tessellation");
    }
    if (has_key(root, "surface")) {
        double tolerance = s.terrain.surface_tolerance_px, min_radius = s.terrain.surface_min_radius_px;
        read_number(root.at("surface"), "tolerance_px", tolerance, path, "surface");
        read_number(root.at("surface"), "min_radius_px", min_radius, path, "surface");
        s.terrain.surface_tolerance_px = float(tolerance), s.terrain.surface_min_radius_px = float(min_radius);
    }
    if (has_key(root, "silhouettes")) {
        double gap = s.lines.silhouette_min_gap;
        read_number(root.at("silhouettes"), "min_gap", gap, path, "silhouettes");
        s.lines.silhouette_min_gap = float(gap);
        read_key(root.at("silhouettes"), "separate_passes", s.lines.separate_passes, path, "silhouettes");
        std::string method = silhouette_method_name(s.lines.silhouette_method);
        read_key(root.at("silhouettes"), "method", method, path, "silhouettes");
        const auto named = silhouette_method_named(method);
        if (!named)
            throw Error("scene", path, "[silhouettes] method must be \"toward-away\", \"adjacency\", \"edge-walk\" or \"object-space\" (got \"" +
                                           method + "\")");
        s.lines.silhouette_method = *named;
    }
    read_crease(root, "creases", s.lines.creases, path);
    read_crease(root, "ridges", s.lines.ridges, path);
    read_hachures(root, s.lines.hachures, path);
    if (has_key(root, "drainage")) read_key(root.at("drainage"), "routing", s.terrain.drainage_routing, path, "drainage");
    if (has_key(root, "cache")) {
        read_key(root.at("cache"), "dir", s.terrain.cache_dir, path, "cache");
        check_local_path("scene", s.terrain.cache_dir);
        if (!s.terrain.cache_dir.empty() && fs::path(s.terrain.cache_dir).is_relative())
            s.terrain.cache_dir = (fs::path(path).parent_path() / s.terrain.cache_dir).lexically_normal().string();
    }
    if (has_key(root, "style")) read_key(root.at("style"), "name", s.style.name, path, "style");
    if (has_key(root, "seed")) {
        if (!root.at("seed").is_integer() || root.at("seed").as_integer() < 0)
            throw Error("scene", path, "seed: must be an integer >= 0");
        s.style.seed = std::uint64_t(root.at("seed").as_integer());
    }
    if (!s.source.mesh.empty()) s.mesh = read_mesh_settings(root, path);
    if (!style.empty()) s.style.name = style;
    s.style.resolved = resolve_style(s.style.name);
    // the [style] table written out as TOML (numbers to 17 digits: they read back exactly)
    if (has_key(root, "style")) apply_style_overrides(s.style.resolved, toml::format(root.at("style")), path);
    return s;
}

}  // namespace

Scene load_scene(const std::string& input, const std::string& style) {
    check_local_path("input", input);
    const bool is_scene = fs::path(input).extension() == ".toml";
    if (is_scene && !fs::exists(input)) throw Error("scene", input, "no such file");
    if (is_scene) return parse_scene_file(input, style);
    Scene s;
    s.source.dem = input;
    if (!style.empty()) s.style.name = style;
    s.style.resolved = resolve_style(s.style.name);
    return s;
}

}  // namespace penink
