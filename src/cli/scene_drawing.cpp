#include "cli/scene_drawing.hpp"

#include <filesystem>

#include "cli/mesh_drawing.hpp"
#include "cli/terrain_drawing.hpp"

namespace penink {

bool is_mesh_scene(const Scene& scene) {
    if (!scene.mesh.empty()) return true;
    std::string ext = std::filesystem::path(scene.dem).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".obj" || ext == ".ply" || ext == ".off";
}

SceneDrawing draw_scene(const Scene& scene, GlContext& context, const Log& log) {
    return is_mesh_scene(scene) ? draw_mesh(scene, context, log) : draw_terrain(scene, context, log);
}

}  // namespace penink
