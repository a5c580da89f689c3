#include "render/surface_geometry.hpp"

#include <vector>

namespace penink {

SurfaceGeometry::SurfaceGeometry(const GlApi& gl, const SurfaceMesh& mesh) : gl_(&gl) {
    std::vector<float> interleaved;
    interleaved.reserve(mesh.pos.size() * 6);
    for (std::size_t i = 0; i < mesh.pos.size(); ++i) {
        const glm::vec3 p = mesh.pos[i], n = mesh.normal[i];
        interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    vertices_ = make_buffer(gl, interleaved.data(), interleaved.size() * sizeof(float));
    indices_ = make_buffer(gl, mesh.tri.data(), mesh.tri.size() * sizeof(glm::uvec3));
    triangles_ = mesh.tri.size();
    vao_ = make_vertex_array(gl);
    const GLuint vao = vao_.id();
    gl.VertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, 6 * sizeof(float));
    gl.VertexArrayElementBuffer(vao, indices_.id());
    for (GLuint a = 0; a < 2; ++a) {
        gl.EnableVertexArrayAttrib(vao, a);
        gl.VertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        gl.VertexArrayAttribBinding(vao, a, 0);
    }
}

void SurfaceGeometry::draw_patches() const {
    gl_->BindVertexArray(vao_.id());
    gl_->PatchParameteri(GL_PATCH_VERTICES, 3);
    gl_->DrawElements(GL_PATCHES, GLsizei(triangles_ * 3), GL_UNSIGNED_INT, nullptr);
    gl_->BindVertexArray(0);
}

}  // namespace penink
