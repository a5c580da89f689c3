#include "render/terrain_renderer_pool.hpp"

#include <algorithm>

namespace penink {

std::shared_ptr<TerrainRenderer> TerrainRendererPool::get(const GlApi& gl, const SurfaceMesh& mesh, int width,
                                                          int height) {
    const auto it = std::find_if(kept_.begin(), kept_.end(),
                                 [&](const Kept& k) { return k.width == width && k.height == height; });
    if (it != kept_.end()) {
        Kept k = std::move(*it);
        kept_.erase(it);
        k.renderer->set_surface(mesh);
        kept_.push_back(std::move(k));
        return kept_.back().renderer;
    }
    if (sizes_ == 0) return std::make_shared<TerrainRenderer>(gl, mesh, width, height);
    if (kept_.size() >= sizes_) kept_.erase(kept_.begin());
    kept_.push_back({width, height, std::make_shared<TerrainRenderer>(gl, mesh, width, height)});
    return kept_.back().renderer;
}

}  // namespace penink
