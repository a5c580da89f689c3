// Reads the first `count` vec4s of a GL buffer back to the CPU: the triangle lists (three corners
// each, metres) of the ID passes of render/id_adjacency_sil.hpp and render/edge_walk_sil.hpp, and
// the latter's silhouette edges (two end points each).
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

#include "render/gl_api.hpp"

namespace penink {

inline std::vector<glm::vec4> read_vec4_buffer(const GlApi& gl, GLuint buffer, std::size_t count) {
    std::vector<glm::vec4> out(count);
    gl.GetNamedBufferSubData(buffer, 0, GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
    return out;
}

}  // namespace penink
