#include "render/edge_walk_sil.hpp"

#include <algorithm>
#include <bit>

#include <glm/gtc/type_ptr.hpp>

#include "render/vec4_buffer.hpp"

namespace penink {

namespace {
constexpr std::size_t corner_bytes = 4 * sizeof(float), triangle_bytes = 3 * corner_bytes, edge_bytes = 2 * corner_bytes;
constexpr std::size_t initial_edges = 4096;

std::uint32_t clamp_u32(std::size_t n) { return std::uint32_t(std::min<std::size_t>(n, 0xffffffffu)); }

glm::mat4 relative_view_projection(const Camera& camera) {  // eye-relative world -> clip
    return glm::mat4(projection_matrix(camera) * glm::dmat4(glm::dmat3(view_matrix(camera))));
}
}  // namespace

EdgeWalkSilPass::EdgeWalkSilPass(const GlApi& gl, int width, int height)
    : gl_(&gl), width_(width), height_(height),
      id_program_(build_program(gl, {"tft_aft.vert.glsl", "tft_aft.tesc.glsl", "tft_aft.tese.glsl",
                                     "edge_walk_sil.geom.glsl", "edge_walk_sil.ids.frag.glsl"})),
      detect_program_(build_program(gl, {"sil.vert.glsl", "edge_walk_sil.detect.frag.glsl"})),
      walk_program_(build_program(gl, {"edge_walk_sil.walk.comp.glsl"})),
      line_program_(build_program(gl, {"edge_walk_sil.lines.vert.glsl", "edge_walk_sil.lines.frag.glsl"})),
      mask_(make_texture(gl, GL_R8, width, height)),
      fb_(make_framebuffer(gl, {mask_.id()}, 0, "edge_walk_sil")),
      empty_vao_(make_vertex_array(gl)),
      counter_(make_buffer(gl, nullptr, 4 * sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      triangles_buf_(make_buffer(gl, nullptr, triangle_bytes, GL_DYNAMIC_DRAW)),
      flags_buf_(make_buffer(gl, nullptr, sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      edges_buf_(make_buffer(gl, nullptr, initial_edges * edge_bytes, GL_DYNAMIC_DRAW)),
      table_buf_(make_buffer(gl, nullptr, sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      pixel_ids_(make_buffer(gl, nullptr, std::size_t(width) * height * 2 * sizeof(std::uint32_t), GL_DYNAMIC_DRAW)),
      capacity_(1), edge_capacity_(initial_edges), table_size_(1), ids_timer_(gl), detect_timer_(gl), walk_timer_(gl), lines_timer_(gl) {}

void EdgeWalkSilPass::reset_buffers() {
    const std::uint32_t counter[4] = {0, clamp_u32(capacity_), 0, clamp_u32(edge_capacity_)};
    gl_->NamedBufferData(counter_.id(), sizeof(counter), counter, GL_DYNAMIC_DRAW);
    const std::vector<std::uint32_t> zeros(std::size_t(width_) * height_ * 2, 0u);
    gl_->NamedBufferData(pixel_ids_.id(), GLsizeiptr(zeros.size() * sizeof(std::uint32_t)), zeros.data(), GL_DYNAMIC_DRAW);
    const std::vector<std::uint32_t> empty_table(table_size_, 0u);
    gl_->NamedBufferData(table_buf_.id(), GLsizeiptr(table_size_ * sizeof(std::uint32_t)), empty_table.data(), GL_DYNAMIC_DRAW);
}

void EdgeWalkSilPass::set_hash_uniforms(GLuint program) const {
    gl_->Uniform1f(uniform_location(*gl_, program, "u_cell"), cell_);
    gl_->Uniform1ui(uniform_location(*gl_, program, "u_table_mask"), std::uint32_t(table_size_ - 1));
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, table_buf_.id());
}

void EdgeWalkSilPass::bind_frame_inputs(GLuint program, GLuint toward_texture, GLuint away_texture) const {
    set_hash_uniforms(program);
    gl_->BindTextureUnit(0, toward_texture);
    gl_->BindTextureUnit(1, away_texture);
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counter_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangles_buf_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, pixel_ids_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, flags_buf_.id());
}

double EdgeWalkSilPass::draw_ids(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                                  GLuint toward_texture, GLuint away_texture) {
    const GLuint p = id_program_.id();
    set_tessellation_uniforms(*gl_, p, camera, tess, width_, height_);
    gl_->Uniform1i(uniform_location(*gl_, p, "u_width"), width_);
    bind_frame_inputs(p, toward_texture, away_texture);
    gl_->BindFramebuffer(GL_FRAMEBUFFER, fb_.id());  // scratch target; the detection rewrites it
    gl_->Disable(GL_DEPTH_TEST), gl_->Disable(GL_BLEND), gl_->Disable(GL_CULL_FACE);
    ids_timer_.begin();
    surface.draw_patches();
    ids_timer_.end();
    gl_->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return ids_timer_.milliseconds();
}

double EdgeWalkSilPass::detect(GLuint toward_texture, GLuint away_texture, const EdgeWalkOptions& options) {
    const GLuint p = detect_program_.id();
    gl_->UseProgram(p);
    gl_->Uniform1f(uniform_location(*gl_, p, "u_tolerance"), options.tolerance);
    gl_->Uniform1i(uniform_location(*gl_, p, "u_radius"), std::clamp(options.radius, 0, 4));
    bind_frame_inputs(p, toward_texture, away_texture);
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, edges_buf_.id());
    gl_->BindFramebuffer(GL_FRAMEBUFFER, fb_.id());
    gl_->BindVertexArray(empty_vao_.id());
    detect_timer_.begin();
    gl_->DrawArrays(GL_TRIANGLES, 0, 3);
    detect_timer_.end();
    gl_->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return detect_timer_.milliseconds();
}

// Rounds of the contour walk, each over the edges the previous one appended.
double EdgeWalkSilPass::walk(const EdgeWalkOptions& options) {
    const GLuint p = walk_program_.id();
    gl_->UseProgram(p);
    gl_->Uniform1f(uniform_location(*gl_, p, "u_tolerance"), options.tolerance);
    set_hash_uniforms(p);
    double ms = 0.0;
    std::uint32_t first = 0, end = 0;
    gl_->GetNamedBufferSubData(counter_.id(), 2 * sizeof(std::uint32_t), sizeof(end), &end);
    for (int round = 0; round < options.walk_rounds && end > first && end <= edge_capacity_; ++round) {
        gl_->Uniform1ui(uniform_location(*gl_, p, "u_first"), first);
        gl_->Uniform1ui(uniform_location(*gl_, p, "u_end"), end);
        walk_timer_.begin();
        gl_->DispatchCompute((end - first + 63) / 64, 1, 1);
        walk_timer_.end();
        gl_->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        ms += walk_timer_.milliseconds();
        first = end;
        gl_->GetNamedBufferSubData(counter_.id(), 2 * sizeof(std::uint32_t), sizeof(end), &end);
    }
    return ms;
}

double EdgeWalkSilPass::draw_lines(const Camera& camera, GLuint toward_texture, const EdgeWalkOptions& options) {
    const GLuint p = line_program_.id();
    const glm::mat4 vp_rel = relative_view_projection(camera);
    gl_->UseProgram(p);
    gl_->UniformMatrix4fv(uniform_location(*gl_, p, "u_view_proj_rel"), 1, GL_FALSE, glm::value_ptr(vp_rel));
    set_camera_uniforms(*gl_, p, camera);
    gl_->Uniform1f(uniform_location(*gl_, p, "u_depth_tolerance"), options.depth_tolerance);
    gl_->BindTextureUnit(0, toward_texture);
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, edges_buf_.id());
    gl_->BindFramebuffer(GL_FRAMEBUFFER, fb_.id());
    gl_->BindVertexArray(empty_vao_.id());
    gl_->LineWidth(1.0f);
    lines_timer_.begin();
    if (edges_ > 0) gl_->DrawArrays(GL_LINES, 0, GLsizei(2 * std::min(edges_, edge_capacity_)));
    lines_timer_.end();
    gl_->BindVertexArray(0);
    gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return lines_timer_.milliseconds();
}

// Reads the triangle and edge counts; grows a buffer that overflowed and returns true (the frame
// must be redrawn: the edge flags live in the triangle pass).
bool EdgeWalkSilPass::grow_on_overflow() {
    std::uint32_t counter[4] = {};
    gl_->GetNamedBufferSubData(counter_.id(), 0, sizeof(counter), counter);
    triangles_ = counter[0], edges_ = counter[2];
    bool grown = false;
    if (triangles_ > capacity_) {
        capacity_ = triangles_ + triangles_ / 4;
        gl_->NamedBufferData(triangles_buf_.id(), GLsizeiptr(capacity_ * triangle_bytes), nullptr, GL_DYNAMIC_DRAW);
        gl_->NamedBufferData(flags_buf_.id(), GLsizeiptr(capacity_ * sizeof(std::uint32_t)), nullptr, GL_DYNAMIC_DRAW);
        table_size_ = std::bit_ceil(6 * capacity_);  // 3 edges per triangle, half full
        grown = true;
    }
    if (edges_ > edge_capacity_) {
        edge_capacity_ = edges_ + edges_ / 4;
        gl_->NamedBufferData(edges_buf_.id(), GLsizeiptr(edge_capacity_ * edge_bytes), nullptr, GL_DYNAMIC_DRAW);
        grown = true;
    }
    return grown;
}

EdgeWalkTimes EdgeWalkSilPass::draw(const SurfaceGeometry& surface, const Camera& camera,
                                      const TessellationOptions& tess, GLuint toward_texture,
                                      GLuint away_texture, const EdgeWalkOptions& options) {
    gl_->Viewport(0, 0, width_, height_);
    // Float differences between two patches' copies of an edge are ~1e-7 of the eye distance.
    cell_ = float(std::max(1.0e-3, 2.0e-5 * camera.far_plane));
    EdgeWalkTimes times;
    for (int attempt = 0; attempt < 3; ++attempt) {  // at most one growth of each buffer
        reset_buffers();
        times.ids_ms += draw_ids(surface, camera, tess, toward_texture, away_texture);
        times.detect_ms += detect(toward_texture, away_texture, options);
        times.walk_ms += walk(options);
        if (!grow_on_overflow()) break;
    }
    times.lines_ms = draw_lines(camera, toward_texture, options);
    return times;
}

void EdgeWalkSilPass::read_ids(std::vector<std::uint32_t>& toward, std::vector<std::uint32_t>& away) const {
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

std::vector<glm::vec4> EdgeWalkSilPass::read_triangles() const {
    return read_vec4_buffer(*gl_, triangles_buf_.id(), std::min(triangles_, capacity_) * 3);
}

std::vector<glm::vec4> EdgeWalkSilPass::read_edges() const {
    return read_vec4_buffer(*gl_, edges_buf_.id(), std::min(edges_, edge_capacity_) * 2);
}

}  // namespace penink
