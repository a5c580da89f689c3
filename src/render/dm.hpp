// DM pass: drainage-vertex rendering ("DM" as the timing tables of Mower, "Concurrent Drainage
// Network Rendering", name the pass; penink batch's timings.md keeps the name): writes, on the
// GPU, the terms of the crease score of eq. 6 for every drainage vertex (sc, ic, fc and the eye
// distance d: core/crease_params.hpp's CreaseTerms; the score is lines/crease_scores.hpp's) and
// tests its visibility against the TFT eye-distance texture, in a compute shader
// (shaders/dm.comp.glsl). The same pass serves the basin-divide vertices of the ridges layer and
// the coastline. Input: world positions (local metres), unit PN normals (zero for a vertex off the
// rendered surface: always hidden), normalised flow; output: per-vertex terms, with distance
// dm_hidden for vertices not visible (outside the frustum, or farther than the TFT surface at
// their pixel; a pixel with no surface counts as visible: silhouette vertices).
#pragma once
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/crease_params.hpp"
#include "core/vertex_run.hpp"
#include "render/gl_objects.hpp"

namespace penink {

struct DmFrame {
    const Camera* camera = nullptr;
    glm::vec3 light{0.0f, 0.0f, 1.0f};  // unit vector towards the light
    GLuint toward_texture = 0;
    float lift_px = 1.0f, tolerance_px = 1.5f;
};

// The vertices a DM pass scores: positions and normals (one each a vertex) and flow (one a vertex,
// or none: 0), laid out as DmVertex on the GPU a chunk at a time (no DmVertex array held beside
// the caller's).
struct DmInput {
    std::span<const glm::vec3> positions, normals;
    std::span<const float> flow;
};

class DmPass {
public:
    DmPass(const GlApi& gl, DmInput vertices);
    // Replaces the vertices (new buffers; the program, compiled once, stays).
    void set_vertices(DmInput vertices);
    // Returns GPU milliseconds; hands `use` the terms (one per vertex) where the pass wrote them:
    // its buffer mapped for reading while `use` runs (no copy of a frame's millions of terms).
    double run(const DmFrame& frame, const std::function<void(std::span<const CreaseTerms>)>& use);
    // The same, the terms copied into `terms`.
    double run(const DmFrame& frame, std::vector<CreaseTerms>& terms);
    std::size_t size() const { return count_; }

private:
    const GlApi* gl_;
    std::size_t count_;
    GlHandle program_, vertices_, terms_;
    GpuTimer timer_;
};

}  // namespace penink
