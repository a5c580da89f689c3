// Thin RAII owners of OpenGL objects (programs, buffers, vertex arrays, textures, framebuffers,
// timer queries) and the shader program builder: a failed compile or link throws
// penink::Error naming the shader file and line (mapped through #include) with the driver log.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.hpp"
#include "render/gl_api.hpp"
#include "render/shader_source.hpp"

namespace penink {

// Owns one GL name; `destroy` deletes it. Move-only.
class GlHandle {
public:
    using Destroy = void (*)(const GlApi&, GLuint);
    GlHandle() = default;
    GlHandle(const GlApi& gl, GLuint id, Destroy destroy) : gl_(&gl), id_(id), destroy_(destroy) {}
    GlHandle(GlHandle&& o) noexcept { *this = std::move(o); }
    GlHandle& operator=(GlHandle&& o) noexcept {
        std::swap(gl_, o.gl_), std::swap(id_, o.id_), std::swap(destroy_, o.destroy_);
        return *this;
    }
    ~GlHandle() { if (id_ && destroy_) destroy_(*gl_, id_); }
    GLuint id() const { return id_; }

private:
    const GlApi* gl_ = nullptr;
    GLuint id_ = 0;
    Destroy destroy_ = nullptr;
};

// Builds a program from embedded shader files (e.g. {"tft_aft.vert.glsl", ...}); the stage is
// taken from the file name (.vert .tesc .tese .geom .frag .comp).
GlHandle build_program(const GlApi& gl, const std::vector<std::string>& files);
// The same from caller-supplied shader texts ({name, text}, e.g. a test's own shader embedded in
// its binary): stage and error locations from each name, `#include`s resolved against the
// embedded shaders (render/shader_source.hpp).
GlHandle build_program_from_text(const GlApi& gl, const std::vector<ShaderFile>& sources);

GlHandle make_buffer(const GlApi& gl, const void* data, std::size_t bytes, GLenum usage = GL_STATIC_DRAW);
GlHandle make_vertex_array(const GlApi& gl);
// 2D texture with immutable storage, nearest filtering, clamp to edge.
GlHandle make_texture(const GlApi& gl, GLenum internal_format, int width, int height);
GlHandle make_framebuffer(const GlApi& gl, const std::vector<GLuint>& colour_textures,
                          GLuint depth_texture, const std::string& name);

// Time of one pass between begin() and end() (glFinish on both sides): the larger of the GL
// timer query and the wall time, in milliseconds; 0 and no finish when the GlApi is untimed.
class GpuTimer {
public:
    explicit GpuTimer(const GlApi& gl);
    void begin();
    void end();
    double milliseconds();

private:
    const GlApi* gl_;
    GlHandle query_;
    std::chrono::steady_clock::time_point start_;
    double wall_ms_ = 0.0;
};

// Uniform setters by name (location looked up each call; passes set a handful per frame).
GLint uniform_location(const GlApi& gl, GLuint program, const char* name);

// Sets the camera uniforms of shaders/common.glsl that `program` declares (u_eye, u_view,
// u_footprint); the program must be in use.
void set_camera_uniforms(const GlApi& gl, GLuint program, const Camera& camera);

}  // namespace penink
