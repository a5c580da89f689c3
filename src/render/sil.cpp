#include "render/sil.hpp"

namespace penink {

SilPass::SilPass(const GlApi& gl, int width, int height)
    : gl_(&gl), width_(width), height_(height),
      program_(build_program(gl, {"sil.vert.glsl", "sil.frag.glsl"})),
      mask_(make_texture(gl, GL_R8, width, height)),
      fb_(make_framebuffer(gl, {mask_.id()}, 0, "sil")),
      empty_vao_(make_vertex_array(gl)), timer_(gl) {}

double SilPass::draw(GLuint toward_texture, GLuint away_texture, float min_gap) {
    gl_->Viewport(0, 0, width_, height_);
    gl_->BindFramebuffer(GL_FRAMEBUFFER, fb_.id());
    gl_->Disable(GL_DEPTH_TEST), gl_->Disable(GL_BLEND), gl_->Disable(GL_CULL_FACE);
    gl_->UseProgram(program_.id());
    gl_->Uniform1f(uniform_location(*gl_, program_.id(), "u_min_gap"), min_gap);
    gl_->BindTextureUnit(0, toward_texture);
    gl_->BindTextureUnit(1, away_texture);
    gl_->BindVertexArray(empty_vao_.id());
    timer_.begin();
    gl_->DrawArrays(GL_TRIANGLES, 0, 3);
    timer_.end();
    gl_->BindVertexArray(0);
    gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return timer_.milliseconds();
}

}  // namespace penink
