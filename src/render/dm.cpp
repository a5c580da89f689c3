#include "render/dm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

namespace penink {

DmPass::DmPass(const GlApi& gl, DmInput vertices)
    : gl_(&gl), count_(0), program_(build_program(gl, {"dm.comp.glsl"})), timer_(gl) {
    set_vertices(vertices);
}

void DmPass::set_vertices(DmInput v) {
    if (v.normals.size() != v.positions.size() || (!v.flow.empty() && v.flow.size() != v.positions.size()))
        throw std::invalid_argument("DM pass: positions, normals and flow differ in count");
    count_ = v.positions.size();
    vertices_ = make_buffer(*gl_, nullptr, std::max<std::size_t>(1, count_) * sizeof(DmVertex));
    constexpr std::size_t chunk = std::size_t(1) << 16;  // vertices laid out at a time (2 MiB)
    std::vector<DmVertex> out(std::min(chunk, count_));
    for (std::size_t i0 = 0; i0 < count_; i0 += chunk) {
        const std::size_t n = std::min(chunk, count_ - i0);
        for (std::size_t j = 0; j < n; ++j) {
            DmVertex& d = out[j];
            d.position = v.positions[i0 + j], d.normal = v.normals[i0 + j];
            d.flow = v.flow.empty() ? 0.0f : v.flow[i0 + j], d.unused = 0.0f;
        }
        gl_->NamedBufferSubData(vertices_.id(), GLintptr(i0 * sizeof(DmVertex)), GLsizeiptr(n * sizeof(DmVertex)), out.data());
    }
    terms_ = make_buffer(*gl_, nullptr, std::max<std::size_t>(1, count_) * sizeof(CreaseTerms), GL_DYNAMIC_READ);
}

double DmPass::run(const DmFrame& f, const std::function<void(std::span<const CreaseTerms>)>& use) {
    static_assert(sizeof(CreaseTerms) == 4 * sizeof(float), "one vec4 per vertex");
    if (count_ == 0) {
        use({});
        return 0.0;
    }
    const Camera& cam = *f.camera;
    const GLuint p = program_.id();
    const auto loc = [&](const char* name) { return uniform_location(*gl_, p, name); };
    gl_->UseProgram(p);
    const glm::mat4 vp(view_projection(cam));
    gl_->UniformMatrix4fv(loc("u_view_proj"), 1, GL_FALSE, glm::value_ptr(vp));
    set_camera_uniforms(*gl_, p, cam);
    gl_->Uniform3f(loc("u_light"), f.light.x, f.light.y, f.light.z);
    gl_->Uniform2f(loc("u_viewport"), float(cam.width), float(cam.height));
    gl_->Uniform1f(loc("u_lift_px"), f.lift_px);
    gl_->Uniform1f(loc("u_tolerance_px"), f.tolerance_px);
    gl_->Uniform1ui(loc("u_count"), GLuint(count_));
    gl_->BindTextureUnit(0, f.toward_texture);
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, vertices_.id());
    gl_->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, terms_.id());
    timer_.begin();
    // 2D grid of work groups: stays under GL_MAX_COMPUTE_WORK_GROUP_COUNT (65535 a side).
    const std::size_t groups = (count_ + 63) / 64, gx = std::min<std::size_t>(groups, 32768);
    gl_->DispatchCompute(GLuint(gx), GLuint((groups + gx - 1) / gx), 1);
    timer_.end();
    gl_->MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // (also what a mapped read needs)
    const GLsizeiptr bytes = GLsizeiptr(count_ * sizeof(CreaseTerms));
    const void* mapped = gl_->MapNamedBufferRange(terms_.id(), 0, bytes, GL_MAP_READ_BIT);
    check_gl_error(*gl_, "DM pass (" + std::to_string(count_) + " vertices)");
    if (!mapped) throw std::runtime_error("DM pass: the terms buffer could not be mapped");
    struct Unmap {  // (also when `use` throws)
        const GlApi& gl;
        GLuint buffer;
        ~Unmap() { gl.UnmapNamedBuffer(buffer); }
    } unmap{*gl_, terms_.id()};
    use({static_cast<const CreaseTerms*>(mapped), count_});
    return timer_.milliseconds();
}

double DmPass::run(const DmFrame& f, std::vector<CreaseTerms>& terms) {
    return run(f, [&terms](std::span<const CreaseTerms> t) { terms.assign(t.begin(), t.end()); });
}

}  // namespace penink
