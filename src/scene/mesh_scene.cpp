#include "scene/mesh_scene.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <glm/geometric.hpp>

#include "scene/terrain_view.hpp"
#include "core/error.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;

std::string scene_name(const Scene& s) { return s.file.empty() ? s.dem : s.file; }

const toml::value* section(const Scene& s, const char* name) {
    if (!s.table.is_table() || !s.table.contains(name)) return nullptr;
    return &s.table.at(name);
}

bool has(const toml::value* t, const char* key) { return t && t->is_table() && t->contains(key); }

[[noreturn]] void bad(const Scene& s, const std::string& sec, const std::string& key, const std::string& what) {
    throw Error("scene", scene_name(s), "[" + sec + "] " + key + ": " + what);
}

double number(const Scene& s, const toml::value& v, const std::string& sec, const std::string& key) {
    if (v.is_integer()) return double(v.as_integer());
    if (v.is_floating() && std::isfinite(v.as_floating())) return v.as_floating();
    bad(s, sec, key, v.is_floating() ? "expected a finite number" : "expected a number");
}

void read_float(const Scene& s, const char* sec, const char* key, float& out) {
    const toml::value* t = section(s, sec);
    if (has(t, key)) out = float(number(s, t->at(key), sec, key));
}

void read_bool(const Scene& s, const char* sec, const char* key, bool& out) {
    const toml::value* t = section(s, sec);
    if (!has(t, key)) return;
    if (!t->at(key).is_boolean()) bad(s, sec, key, "expected true or false");
    out = t->at(key).as_boolean();
}

std::string read_string(const Scene& s, const char* sec, const char* key, std::string fallback) {
    const toml::value* t = section(s, sec);
    if (!has(t, key)) return fallback;
    if (!t->at(key).is_string()) bad(s, sec, key, "expected a string");
    return t->at(key).as_string().str;
}

std::optional<glm::dvec3> read_vec3(const Scene& s, const char* sec, const char* key) {
    const toml::value* t = section(s, sec);
    if (!has(t, key)) return std::nullopt;
    const toml::value& v = t->at(key);
    if (!v.is_array() || v.as_array().size() != 3) bad(s, sec, key, "expected 3 numbers");
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i) {
        const toml::value& c = v.as_array()[i];
        if (!c.is_integer() && !c.is_floating()) bad(s, sec, key, "expected 3 numbers");
        out[i] = number(s, c, sec, key);
    }
    return out;
}

void read_materials(const Scene& s, MeshScene& ms) {
    const toml::value* t = section(s, "textures");
    if (!has(t, "material")) return;
    const toml::value& m = t->at("material");
    if (!m.is_table()) bad(s, "textures", "material", "expected material.NAME = \"texture\"");
    for (const auto& [name, v] : m.as_table()) {
        if (!v.is_string()) bad(s, "textures", "material." + name, "expected a texture name");
        ms.materials[name] = v.as_string().str;
    }
}

void check_ranges(const Scene& s, const MeshScene& ms) {
    if (!(ms.pel_threshold >= 0.0f)) bad(s, "pels", "threshold", "must be >= 0");
    if (ms.smoothing < 0 || ms.smoothing > 1000) bad(s, "pels", "smoothing", "must be between 0 and 1000");
    if (!(ms.normal_filter >= 0.0f && ms.normal_filter <= 20.0f))
        bad(s, "pels", "normal_filter", "must be between 0 and 20 (mean edge lengths)");
    if (!(ms.line_strength >= 0.0f && ms.line_strength <= 1e6f)) bad(s, "pels", "line_strength", "must be >= 0");
    if (!(ms.crease_angle >= 0.0f && ms.crease_angle <= 180.0f))
        bad(s, "features", "crease_angle", "must be between 0 and 180 degrees");
    if (!(ms.texture_confidence >= 0.0f && ms.texture_confidence <= 1.0f))
        bad(s, "textures", "confidence", "must be between 0 and 1");
    if (ms.texture_scale && !(*ms.texture_scale > 0.0f)) bad(s, "textures", "scale", "must be > 0");
    if (ms.light && !(glm::length(*ms.light) > 0.0)) bad(s, "light", "direction", "must not be zero");
}

}  // namespace

MeshScene load_mesh_scene(const Scene& s) {
    MeshScene ms;
    ms.path = s.mesh.empty() ? s.dem : s.mesh;
    const std::string up = read_string(s, "mesh", "up", "y");
    if (up != "y" && up != "z") bad(s, "mesh", "up", "use \"y\" or \"z\"");
    ms.y_up = up == "y";
    ms.up = ms.y_up ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    float subdivide = 0.0f;
    read_float(s, "mesh", "subdivide", subdivide);
    if (subdivide < 0.0f || subdivide > 4.0f || subdivide != std::floor(subdivide))
        bad(s, "mesh", "subdivide", "must be a whole number from 0 to 4");
    ms.subdivide = int(subdivide);
    ms.eye = read_vec3(s, "camera", "eye");
    ms.target = read_vec3(s, "camera", "target");
    if (auto u = read_vec3(s, "camera", "up")) ms.up = *u;
    ms.light = read_vec3(s, "light", "direction");
    read_bool(s, "pels", "enabled", ms.pels);
    read_float(s, "pels", "threshold", ms.pel_threshold);
    float smoothing = float(ms.smoothing);
    read_float(s, "pels", "smoothing", smoothing);
    ms.smoothing = int(smoothing);
    read_float(s, "pels", "normal_filter", ms.normal_filter);
    read_float(s, "pels", "line_strength", ms.line_strength);
    read_bool(s, "features", "enabled", ms.features);
    read_float(s, "features", "crease_angle", ms.crease_angle);
    read_bool(s, "textures", "enabled", ms.textures);
    read_float(s, "textures", "threshold", ms.texture_threshold);
    read_float(s, "textures", "confidence", ms.texture_confidence);
    float scale = 0.0f;
    read_float(s, "textures", "scale", scale);
    if (has(section(s, "textures"), "scale")) ms.texture_scale = scale;
    ms.texture_library = read_string(s, "textures", "library", "");
    if (!ms.texture_library.empty() && fs::path(ms.texture_library).is_relative() && !s.file.empty())
        ms.texture_library = (fs::path(s.file).parent_path() / ms.texture_library).lexically_normal().string();
    read_materials(s, ms);
    check_ranges(s, ms);
    return ms;
}

glm::dvec3 mesh_to_world(const MeshScene& ms, const glm::dvec3& v) {
    return ms.y_up ? glm::dvec3(v.x, -v.z, v.y) : v;
}

Camera mesh_camera(const Scene& s, const MeshScene& ms, const std::vector<glm::vec3>& points,
                   const glm::dvec3& lo, const glm::dvec3& hi) {
    const SceneCamera& sc = s.camera;
    if (sc.projection == Projection::orthographic)
        throw Error("scene", scene_name(s), "orthographic views are for DEMs: a mesh is drawn in perspective");
    if (ms.eye.has_value() != ms.target.has_value())
        throw Error("scene", scene_name(s), "camera eye and target go together (give both or neither)");
    if (!ms.eye) {
        const std::vector<glm::dvec3> pts(points.begin(), points.end());
        return frame_points(pts, {.azimuth = sc.azimuth.value_or(default_view_azimuth),
                                  .altitude = sc.altitude.value_or(default_view_altitude),
                                  .fov = sc.fov,
                                  .width = sc.width,
                                  .height = sc.height,
                                  .fill = 0.9});
    }
    const glm::dvec3 eye = mesh_to_world(ms, *ms.eye), d = mesh_to_world(ms, *ms.target) - eye;
    if (!(glm::length(d) > 0.0)) throw Error("scene", scene_name(s), "camera eye and target coincide");
    const glm::dvec3 dir = glm::normalize(d), up = mesh_to_world(ms, ms.up);
    if (!(glm::length(up) > 0.0) || (std::abs(dir.z) < 0.99 && glm::normalize(up).z < 0.5))
        throw Error("scene", scene_name(s),
                    "camera up must be roughly the mesh's up axis (roll is not supported)");
    Camera cam;
    cam.eye = eye;
    const glm::dvec2 angles = angles_from_direction(dir);
    cam.azimuth = angles.x, cam.altitude = angles.y;
    cam.fov = sc.fov, cam.width = sc.width, cam.height = sc.height;
    fit_depth_range(cam, lo, hi);
    return cam;
}

std::string find_texture_library(const Scene& s, const MeshScene& ms) {
    if (!ms.texture_library.empty()) return ms.texture_library;
    if (const char* env = std::getenv("PENINK_TEXTURES"); env && *env) return env;
    std::vector<fs::path> candidates;
    if (!s.file.empty()) candidates.push_back(fs::path(s.file).parent_path() / "textures");
    candidates.push_back(fs::path(ms.path).parent_path() / ".." / "textures");
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        candidates.push_back(exe.parent_path() / ".." / "examples" / "textures");
        candidates.push_back(exe.parent_path() / ".." / "share" / "penink" / "examples" / "textures");  // installed
    }
    for (const fs::path& c : candidates)
        if (fs::is_directory(c, ec)) return c.lexically_normal().string();
    return "";
}

}  // namespace penink
