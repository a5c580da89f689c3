// DM pass: drainage-vertex rendering ("DM" as the timing tables of Mower, "Concurrent Drainage
// Network Rendering", name the pass; penink batch's timings.md keeps the name): scores drainage vertices on the GPU with the crease score of
// conventions.md (rs = (sw sc + iw ic + fw fc)/3 - rs_min(d), or divided by sw + iw + fw with
// normalisation "paper": core/crease_params.hpp; "rank" takes the terms from one run per term,
// scene/drainage_lines.cpp) and tests their visibility against
// the TFT eye-distance texture, in a compute shader (shaders/dm.comp.glsl). The same pass scores
// basin-divide vertices for the ridges layer. Input: world positions (local metres), unit PN
// normals (zero for a vertex off the rendered surface: always hidden), normalised flow; output:
// per-vertex rs, or dm_hidden for vertices not visible (outside the frustum, or farther than the
// TFT surface at their pixel; a pixel with no surface counts as visible: silhouette vertices).
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/crease_params.hpp"
#include "render/gl_objects.hpp"

namespace penink {

inline constexpr float dm_hidden = -1.0e30f;

struct DmVertex {
    glm::vec3 position;
    float flow = 0.0f;
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float unused = 0.0f;
};


struct DmFrame {
    const Camera* camera = nullptr;
    glm::vec3 light{0.0f, 0.0f, 1.0f};  // unit vector towards the light
    float max_distance = 1.0f;          // D, metres
    GLuint toward_texture = 0;
    float lift_px = 1.0f, tolerance_px = 1.5f;
};

class DmPass {
public:
    DmPass(const GlApi& gl, const std::vector<DmVertex>& vertices);
    // Returns GPU milliseconds; fills `scores` (one per vertex).
    double run(const DmFrame& frame, const CreaseParams& score, std::vector<float>& scores);
    std::size_t size() const { return count_; }

private:
    const GlApi* gl_;
    std::size_t count_;
    GlHandle program_, vertices_, scores_;
    GpuTimer timer_;
};

}  // namespace penink
