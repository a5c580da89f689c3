// PN evaluation on the GPU (shaders/pn_eval.comp.glsl): positions and unit normals of PN patches
// (Vlachos 2001) at barycentric points, computed by the same GLSL functions the tessellation
// stages use. Lets tests hold the GPU maths to the CPU reference (src/surface/pn_triangle.hpp).
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
