#include "scene/frame_source.hpp"

#include <filesystem>

#include "core/checked_blocks.hpp"

#include "scene/mesh_frames.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_keep.hpp"

namespace penink {

bool is_mesh_scene(const Scene& scene) {
    if (!scene.source.mesh.empty()) return true;
    std::string ext = std::filesystem::path(scene.source.dem).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".obj" || ext == ".ply" || ext == ".off";
}

SceneView open_scene_view(Scene& scene, GlContext& context, const Log& log, TerrainKeep* keep) {
    return is_mesh_scene(scene) ? open_mesh_view(scene, context, log) : open_terrain_view(scene, context, log, keep);
}

SceneDrawing draw_scene(Scene& scene, GlContext& context, const Log& log, TerrainKeep* keep) {
    try {
        SceneView view = open_scene_view(scene, context, log, keep);
        return view.frames->draw(view.camera, scene);
    } catch (const DamagedBlockError& e) {
        log.info("terrain: " + e.file() + ": damaged terrain cache (block checksum); building");
        if (keep) keep->forget_terrain();  // it holds the damaged cache open
        std::error_code ec;
        std::filesystem::remove(e.file(), ec);
    }
    SceneView view = open_scene_view(scene, context, log, keep);
    return view.frames->draw(view.camera, scene);
}

}  // namespace penink
