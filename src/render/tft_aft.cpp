#include "render/tft_aft.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "render/shader_source.hpp"

namespace penink {

namespace {
constexpr float far_value = 1.0e30f;
}

TftAftPass::TftAftPass(const GlApi& gl, int width, int height)
    : gl_(&gl), width_(width), height_(height),
      program_(build_program(gl, {"tft_aft.vert.glsl", "tft_aft.tesc.glsl", "tft_aft.tese.glsl",
                                  "tft_aft.frag.glsl"})),
      toward_(make_texture(gl, GL_R32F, width, height)),
      away_(make_texture(gl, GL_R32F, width, height)),
      depth_(make_texture(gl, GL_DEPTH_COMPONENT32F, width, height)),
      combined_fb_(make_framebuffer(gl, {toward_.id(), away_.id()}, 0, "tft_aft")),
      toward_fb_(make_framebuffer(gl, {toward_.id()}, depth_.id(), "tft")),
      away_fb_(make_framebuffer(gl, {away_.id()}, depth_.id(), "aft")),
      tft_timer_(gl), aft_timer_(gl) {}

void set_tessellation_uniforms(const GlApi& gl, GLuint p, const Camera& camera, const TessellationOptions& tess,
                               int width, int height) {
    const glm::mat4 vp(view_projection(camera));
    gl.UseProgram(p);
    gl.UniformMatrix4fv(uniform_location(gl, p, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(vp));
    gl.Uniform2f(uniform_location(gl, p, "u_viewport"), float(width), float(height));
    gl.Uniform1f(uniform_location(gl, p, "u_target_px"), tess.target_edge_px);
    gl.Uniform1f(uniform_location(gl, p, "u_max_level"), float(std::max(1, tess.max_level)));
    gl.Uniform1i(uniform_location(gl, p, "u_no_cull"), tess.cull_patches ? 0 : 1);
    gl.Uniform1i(uniform_location(gl, p, "u_patch_level"), tess.per_patch_level ? 1 : 0);
    set_camera_uniforms(gl, p, camera);
}

void TftAftPass::set_uniforms(const Camera& camera, const TessellationOptions& tess, int mode) const {
    set_tessellation_uniforms(*gl_, program_.id(), camera, tess, width_, height_);
    gl_->Uniform1i(uniform_location(*gl_, program_.id(), "u_mode"), mode);
}

TftAftTimes TftAftPass::draw(const SurfaceGeometry& surface, const Camera& camera,
                             const TessellationOptions& tess, bool separate_passes) {
    const float far4[4] = {far_value, far_value, far_value, far_value};
    const float one = 1.0f;
    gl_->Viewport(0, 0, width_, height_);
    TftAftTimes times;
    if (!separate_passes) {
        set_uniforms(camera, tess, 0);
        gl_->BindFramebuffer(GL_FRAMEBUFFER, combined_fb_.id());
        gl_->ClearNamedFramebufferfv(combined_fb_.id(), GL_COLOR, 0, far4);
        gl_->ClearNamedFramebufferfv(combined_fb_.id(), GL_COLOR, 1, far4);
        gl_->Disable(GL_DEPTH_TEST), gl_->Disable(GL_CULL_FACE);
        gl_->Enable(GL_BLEND), gl_->BlendEquation(GL_MIN);
        tft_timer_.begin();
        surface.draw_patches();
        tft_timer_.end();
        gl_->Disable(GL_BLEND), gl_->BlendEquation(GL_FUNC_ADD);
        times.tft_ms = tft_timer_.milliseconds();
    } else {
        gl_->Enable(GL_DEPTH_TEST), gl_->DepthFunc(GL_LESS), gl_->Enable(GL_CULL_FACE);
        GpuTimer* timers[2] = {&tft_timer_, &aft_timer_};
        const GLuint fbs[2] = {toward_fb_.id(), away_fb_.id()};
        for (int i = 0; i < 2; ++i) {
            set_uniforms(camera, tess, i + 1);
            gl_->BindFramebuffer(GL_FRAMEBUFFER, fbs[i]);
            gl_->ClearNamedFramebufferfv(fbs[i], GL_COLOR, 0, far4);
            gl_->ClearNamedFramebufferfv(fbs[i], GL_DEPTH, 0, &one);
            gl_->CullFace(i == 0 ? GL_BACK : GL_FRONT);
            timers[i]->begin();
            surface.draw_patches();
            timers[i]->end();
        }
        gl_->Disable(GL_DEPTH_TEST), gl_->Disable(GL_CULL_FACE);
        times.tft_ms = tft_timer_.milliseconds(), times.aft_ms = aft_timer_.milliseconds();
    }
    gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return times;
}

}  // namespace penink
