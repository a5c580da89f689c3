#include "render/adjacency_sil.hpp"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

namespace penink {

namespace {
constexpr std::size_t corner_bytes = 4 * sizeof(float), triangle_bytes = 3 * corner_bytes;
}

AdjacencySilPass::AdjacencySilPass(const GlApi& gl, int width, int height)
    : gl_(&gl), width_(width), height_(height),
      id_program_(build_program(gl, {"tft_aft.vert.glsl", "tft_aft.tesc.glsl", "tft_aft.tese.glsl",
                                     "adjacency_sil.geom.glsl", "adjacency_sil.ids.frag.glsl"})),
      detect_program_(build_program(gl, {"sil.vert.glsl", "adjacency_sil.detect.frag.glsl"})),
      mask_(make_texture(gl, GL_R8, width, height)),
      fb_(make_framebuffer(gl, {mask_.id()}, 0, "adjacency_sil")),
      empty_vao_(make_vertex_array(gl)),
      counter_(make_buffer(gl, nullptr, 2 * sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      triangles_buf_(make_buffer(gl, nullptr, triangle_bytes, GL_DYNAMIC_DRAW)),
      pixel_ids_(make_buffer(gl, nullptr, std::size_t(width) * height * 2 * sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      capacity_(1), ids_timer_(gl), detect_timer_(gl) {}

void AdjacencySilPass::reset_buffers() {
    const std::uint32_t counter[2] = {0, std::uint32_t(std::min<std::size_t>(capacity_, 0xffffffffu))};
    gl_->NamedBufferData(counter_.id(), sizeof(counter), counter, GL_DYNAMIC_DRAW);
    const std::vector<std::uint32_t> zeros(std::size_t(width_) * height_ * 2, 0u);
    gl_->NamedBufferData(pixel_ids_.id(), GLsizeiptr(zeros.size() * sizeof(std::uint32_t)), zeros.data(), GL_DYNAMIC_DRAW);
}

double AdjacencySilPass::draw_ids(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                                  GLuint toward_texture, GLuint away_texture) {
    const GLuint p = id_program_.id();
    const glm::mat4 vp(view_projection(camera));
    const glm::vec3 eye(camera.eye);
    gl_->UseProgram(p);
    gl_->UniformMatrix4fv(uniform_location(*gl_, p, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(vp));
    gl_->Uniform2f(uniform_location(*gl_, p, "u_viewport"), float(width_), float(height_));
    gl_->Uniform1f(uniform_location(*gl_, p, "u_target_px"), tess.target_edge_px);
    gl_->Uniform1f(uniform_location(*gl_, p, "u_max_level"), float(std::max(1, tess.max_level)));
    gl_->Uniform3f(uniform_location(*gl_, p, "u_eye"), eye.x, eye.y, eye.z);
    gl_->Uniform1i(uniform_location(*gl_, p, "u_width"), width_);
    gl_->BindTextureUnit(0, toward_texture);
    gl_->BindTextureUnit(1, away_texture);
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counter_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangles_buf_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, pixel_ids_.id());
    gl_->BindFramebuffer(GL_FRAMEBUFFER, fb_.id());  // scratch target; the detection rewrites it
    gl_->Disable(GL_DEPTH_TEST), gl_->Disable(GL_BLEND), gl_->Disable(GL_CULL_FACE);
    ids_timer_.begin();
    surface.draw_patches();
    ids_timer_.end();
    gl_->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return ids_timer_.milliseconds();
}

double AdjacencySilPass::detect(const Camera& camera, GLuint toward_texture, GLuint away_texture,
                                const AdjacencyOptions& options) {
    const GLuint p = detect_program_.id();
    const glm::dmat4 rel = projection_matrix(camera) * glm::dmat4(glm::dmat3(view_matrix(camera)));
    const glm::mat4 vp_rel(rel);
    gl_->UseProgram(p);
    gl_->UniformMatrix4fv(uniform_location(*gl_, p, "u_view_proj_rel"), 1, GL_FALSE, glm::value_ptr(vp_rel));
    gl_->Uniform2f(uniform_location(*gl_, p, "u_viewport"), float(width_), float(height_));
    gl_->Uniform1f(uniform_location(*gl_, p, "u_tolerance"), options.tolerance);
    gl_->Uniform1f(uniform_location(*gl_, p, "u_half_width"), options.half_width);
    gl_->BindTextureUnit(0, toward_texture);
    gl_->BindTextureUnit(1, away_texture);
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangles_buf_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, pixel_ids_.id());
    gl_->BindFramebuffer(GL_FRAMEBUFFER, fb_.id());
    gl_->BindVertexArray(empty_vao_.id());
    detect_timer_.begin();
    gl_->DrawArrays(GL_TRIANGLES, 0, 3);
    detect_timer_.end();
    gl_->BindVertexArray(0);
    gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return detect_timer_.milliseconds();
}

AdjacencyTimes AdjacencySilPass::draw(const SurfaceGeometry& surface, const Camera& camera,
                                      const TessellationOptions& tess, GLuint toward_texture,
                                      GLuint away_texture, const AdjacencyOptions& options) {
    gl_->Viewport(0, 0, width_, height_);
    AdjacencyTimes times;
    for (int attempt = 0; attempt < 2; ++attempt) {
        reset_buffers();
        times.ids_ms += draw_ids(surface, camera, tess, toward_texture, away_texture);
        std::uint32_t count = 0;
        gl_->GetNamedBufferSubData(counter_.id(), 0, sizeof(count), &count);
        triangles_ = count;
        if (count <= capacity_) break;
        capacity_ = std::size_t(count) + count / 4;  // grow once and redraw the frame
        gl_->NamedBufferData(triangles_buf_.id(), GLsizeiptr(capacity_ * triangle_bytes), nullptr, GL_DYNAMIC_DRAW);
    }
    times.detect_ms = detect(camera, toward_texture, away_texture, options);
    return times;
}

void AdjacencySilPass::read_ids(std::vector<std::uint32_t>& toward, std::vector<std::uint32_t>& away) const {
    const std::size_t n = std::size_t(width_) * height_;
    std::vector<std::uint32_t> both(2 * n);
    gl_->GetNamedBufferSubData(pixel_ids_.id(), 0, GLsizeiptr(both.size() * sizeof(std::uint32_t)), both.data());
    toward.assign(n, 0), away.assign(n, 0);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const std::size_t src = std::size_t(y) * width_ + x, dst = std::size_t(height_ - 1 - y) * width_ + x;
            toward[dst] = both[2 * src], away[dst] = both[2 * src + 1];
        }
}

}  // namespace penink

namespace penink {

std::vector<glm::vec4> AdjacencySilPass::read_triangles() const {
    std::vector<glm::vec4> out(std::min(triangles_, capacity_) * 3);
    gl_->GetNamedBufferSubData(triangles_buf_.id(), 0, GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
    return out;
}

}  // namespace penink
