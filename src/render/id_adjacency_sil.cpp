#include "render/id_adjacency_sil.hpp"

#include <algorithm>

#include "render/vec4_buffer.hpp"

namespace penink {

namespace {
constexpr std::size_t triangle_bytes = 3 * 4 * sizeof(float);
constexpr std::size_t initial_triangles = 1 << 16;
}  // namespace

IdAdjacencySilPass::IdAdjacencySilPass(const GlApi& gl, int width, int height)
    : gl_(&gl), width_(width), height_(height),
      id_program_(build_program(gl, {"tft_aft.vert.glsl", "tft_aft.tesc.glsl", "tft_aft.tese.glsl",
                                     "id_adjacency_sil.geom.glsl", "id_adjacency_sil.ids.frag.glsl"})),
      pixel_program_(build_program(gl, {"sil.vert.glsl", "id_adjacency_sil.frag.glsl"})),
      ids_(make_texture(gl, GL_R32UI, width, height)),
      depth_(make_texture(gl, GL_DEPTH_COMPONENT32F, width, height)),
      id_fb_(make_framebuffer(gl, {ids_.id()}, depth_.id(), "id_adjacency_sil ids")),
      mask_(make_texture(gl, GL_R8, width, height)),
      mask_fb_(make_framebuffer(gl, {mask_.id()}, 0, "id_adjacency_sil")),
      empty_vao_(make_vertex_array(gl)),
      counter_(make_buffer(gl, nullptr, 2 * sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      triangles_buf_(make_buffer(gl, nullptr, initial_triangles * triangle_bytes, GL_DYNAMIC_DRAW)),
      capacity_(initial_triangles), ids_timer_(gl), pixels_timer_(gl) {}

// The ID raster and the triangle list; redrawn once with a larger list when it overflowed.
double IdAdjacencySilPass::draw_ids(const SurfaceGeometry& surface, const Camera& camera,
                                    const TessellationOptions& tess) {
    const GLuint p = id_program_.id();
    const std::uint32_t no_id[4] = {0, 0, 0, 0};
    const float far_depth = 1.0f;
    double ms = 0.0;
    for (int attempt = 0; attempt < 2; ++attempt) {
        const std::uint32_t counter[2] = {0, std::uint32_t(std::min<std::size_t>(capacity_, 0xffffffffu))};
        gl_->NamedBufferData(counter_.id(), sizeof(counter), counter, GL_DYNAMIC_DRAW);
        set_tessellation_uniforms(*gl_, p, camera, tess, width_, height_);
        gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counter_.id());
        gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangles_buf_.id());
        gl_->BindFramebuffer(GL_FRAMEBUFFER, id_fb_.id());
        gl_->ClearNamedFramebufferuiv(id_fb_.id(), GL_COLOR, 0, no_id);
        gl_->ClearNamedFramebufferfv(id_fb_.id(), GL_DEPTH, 0, &far_depth);
        gl_->Enable(GL_DEPTH_TEST), gl_->DepthFunc(GL_LESS), gl_->DepthMask(GL_TRUE);
        gl_->Disable(GL_BLEND), gl_->Disable(GL_CULL_FACE);
        ids_timer_.begin();
        surface.draw_patches();
        ids_timer_.end();
        gl_->Disable(GL_DEPTH_TEST);
        gl_->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        ms += ids_timer_.milliseconds();
        std::uint32_t count = 0;
        gl_->GetNamedBufferSubData(counter_.id(), 0, sizeof(count), &count);
        triangles_ = count;
        if (triangles_ <= capacity_) break;
        capacity_ = triangles_ + triangles_ / 4;
        gl_->NamedBufferData(triangles_buf_.id(), GLsizeiptr(capacity_ * triangle_bytes), nullptr, GL_DYNAMIC_DRAW);
    }
    return ms;
}

double IdAdjacencySilPass::mark_pixels(GLuint toward_texture, GLuint away_texture, const IdAdjacencyOptions& options) {
    const GLuint p = pixel_program_.id();
    gl_->UseProgram(p);
    gl_->Uniform1f(uniform_location(*gl_, p, "u_crack_tolerance"), std::max(0.0f, options.crack_tolerance));
    gl_->Uniform1i(uniform_location(*gl_, p, "u_mesh_borders"), options.mesh_borders ? 1 : 0);
    gl_->Uniform1i(uniform_location(*gl_, p, "u_vertex_adjacency"), options.vertex_adjacency ? 1 : 0);
    gl_->Uniform1ui(uniform_location(*gl_, p, "u_triangles"), std::uint32_t(std::min(triangles_, capacity_)));
    gl_->BindTextureUnit(0, toward_texture);
    gl_->BindTextureUnit(1, away_texture);
    gl_->BindTextureUnit(2, ids_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangles_buf_.id());
    gl_->BindFramebuffer(GL_FRAMEBUFFER, mask_fb_.id());
    gl_->BindVertexArray(empty_vao_.id());
    pixels_timer_.begin();
    gl_->DrawArrays(GL_TRIANGLES, 0, 3);
    pixels_timer_.end();
    gl_->BindVertexArray(0);
    gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return pixels_timer_.milliseconds();
}

IdAdjacencyTimes IdAdjacencySilPass::draw(const SurfaceGeometry& surface, const Camera& camera,
                                          const TessellationOptions& tess, GLuint toward_texture,
                                          GLuint away_texture, const IdAdjacencyOptions& options) {
    gl_->Viewport(0, 0, width_, height_);
    IdAdjacencyTimes times;
    times.ids_ms = draw_ids(surface, camera, tess);
    times.pixels_ms = mark_pixels(toward_texture, away_texture, options);
    return times;
}

std::vector<std::uint32_t> IdAdjacencySilPass::read_ids() const {
    std::vector<std::uint32_t> raw(std::size_t(width_) * height_), out(raw.size());
    gl_->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_->GetTextureImage(ids_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(raw.size() * sizeof(std::uint32_t)),
                         raw.data());
    for (int y = 0; y < height_; ++y)
        std::copy_n(raw.begin() + std::ptrdiff_t(y) * width_, width_,
                    out.begin() + std::ptrdiff_t(height_ - 1 - y) * width_);
    return out;
}

std::vector<glm::vec4> IdAdjacencySilPass::read_triangles() const {
    return read_vec4_buffer(*gl_, triangles_buf_.id(), std::min(triangles_, capacity_) * 3);
}

}  // namespace penink
