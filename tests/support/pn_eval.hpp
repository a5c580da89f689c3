// PN evaluation on the GPU, for tests (tests/support/shaders/pn_eval.comp.glsl, embedded in the
// test-support library): positions and unit normals of PN patches (Vlachos 2001) at barycentric
// points (t0, t1, t2 weighting p[0], p[1], p[2]), in the patch's own frame and units, computed by
// the same GLSL functions the tessellation stages use (shaders/common.glsl). Lets tests hold the
// GPU maths to the CPU reference (src/surface/pn_triangle.hpp). Needs a current GL 4.5 context.
#pragma once
#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "render/gl_api.hpp"

namespace penink {

struct PnQuery {
    std::array<glm::vec3, 3> p, n;  // patch vertices and vertex normals
    glm::vec3 bary{1.0f / 3.0f};
};

struct PnSample {
    glm::vec3 position, normal;
};

std::vector<PnSample> evaluate_pn_on_gpu(const GlApi& gl, const std::vector<PnQuery>& queries);

}  // namespace penink
