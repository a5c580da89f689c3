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

std::string scene_name(const Scene& s) { return s.source.file.empty() ? s.source.dem : s.source.file; }

}  // namespace

const std::string& mesh_file(const Scene& scene) {
    return scene.source.mesh.empty() ? scene.source.dem : scene.source.mesh;
}

glm::dvec3 mesh_to_world(const MeshSettings& ms, const glm::dvec3& v) {
    return ms.y_up ? glm::dvec3(v.x, -v.z, v.y) : v;
}

Camera mesh_camera(const Scene& s, const std::vector<glm::vec3>& points,
                   const glm::dvec3& lo, const glm::dvec3& hi) {
    const SceneCamera& sc = s.view.camera;
    const MeshSettings& ms = s.mesh;
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

std::string find_texture_library(const Scene& s) {
    if (!s.mesh.texture_library.empty()) return s.mesh.texture_library;
    if (const char* env = std::getenv("PENINK_TEXTURES"); env && *env) return env;
    std::vector<fs::path> candidates;
    if (!s.source.file.empty()) candidates.push_back(fs::path(s.source.file).parent_path() / "textures");
    candidates.push_back(fs::path(mesh_file(s)).parent_path() / ".." / "textures");
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
