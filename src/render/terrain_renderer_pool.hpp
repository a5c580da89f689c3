// Terrain renderers kept for the frames to come, one per image size: a process that draws one
// view after another (penink preview: full frames and smaller ones while the mouse drags) makes
// and compiles each size's passes once; llvmpipe compiles a program's shaders again for every new
// program object, at its first draw. A renderer is state-free between frames (each pass clears
// what it draws into), so a kept one draws what a new one would.
#pragma once
#include <cstddef>
#include <memory>
#include <vector>

#include "render/terrain_renderer.hpp"

namespace penink {

class TerrainRendererPool {
public:
    // `sizes`: how many image sizes are kept (the ones asked for last).
    explicit TerrainRendererPool(std::size_t sizes = 2) : sizes_(sizes) {}

    // A renderer of width x height with `mesh` uploaded: the one kept for that size, else a new
    // one, kept in place of the size asked for least recently when `sizes` are kept already.
    std::shared_ptr<TerrainRenderer> get(const GlApi& gl, const SurfaceMesh& mesh, int width, int height);
    std::size_t size() const { return kept_.size(); }

private:
    struct Kept {
        int width = 0, height = 0;
        std::shared_ptr<TerrainRenderer> renderer;
    };
    std::vector<Kept> kept_;  // the one asked for last at the back
    std::size_t sizes_;
};

}  // namespace penink
