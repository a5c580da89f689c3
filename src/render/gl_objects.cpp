#include "render/gl_objects.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "render/shader_source.hpp"

namespace penink {

namespace {

GLenum stage_of(const std::string& file) {
    const auto has = [&](const char* s) { return file.find(s) != std::string::npos; };
    if (has(".vert.")) return GL_VERTEX_SHADER;
    if (has(".tesc.")) return GL_TESS_CONTROL_SHADER;
    if (has(".tese.")) return GL_TESS_EVALUATION_SHADER;
    if (has(".geom.")) return GL_GEOMETRY_SHADER;
    if (has(".frag.")) return GL_FRAGMENT_SHADER;
    if (has(".comp.")) return GL_COMPUTE_SHADER;
    throw Error("render", file, "cannot tell the shader stage from the file name", ExitCode::internal);
}

// Driver logs end with newlines; the error stays one line.
std::string one_line(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    for (char& c : s) if (c == '\n') c = ' ';
    return s;
}

GLuint compile_shader(const GlApi& gl, const std::string& file, const AssembledShader& src) {
    const GLuint shader = gl.CreateShader(stage_of(file));
    const char* text = src.text.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint ok = 0;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::string log(4096, '\0');
        GLsizei len = 0;
        gl.GetShaderInfoLog(shader, GLsizei(log.size()), &len, log.data());
        log.resize(std::size_t(len));
        gl.DeleteShader(shader);
        throw Error("render", file, "shader compile failed: " + one_line(map_log_to_files(log, src.files)),
                    ExitCode::internal);
    }
    return shader;
}

// files[i] is assembled as sources[i].
GlHandle link_program(const GlApi& gl, const std::vector<std::string>& files,
                      const std::vector<AssembledShader>& sources) {
    GlHandle program(gl, gl.CreateProgram(), [](const GlApi& g, GLuint id) { g.DeleteProgram(id); });
    std::vector<GLuint> shaders;
    try {
        for (std::size_t i = 0; i < files.size(); ++i) {
            shaders.push_back(compile_shader(gl, files[i], sources[i]));
            gl.AttachShader(program.id(), shaders.back());
        }
    } catch (...) {
        for (GLuint s : shaders) gl.DeleteShader(s);
        throw;
    }
    gl.LinkProgram(program.id());
    for (GLuint s : shaders) gl.DeleteShader(s);
    GLint ok = 0;
    gl.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        std::string log(4096, '\0');
        GLsizei len = 0;
        gl.GetProgramInfoLog(program.id(), GLsizei(log.size()), &len, log.data());
        log.resize(std::size_t(len));
        throw Error("render", files.front(), "program link failed: " + one_line(log), ExitCode::internal);
    }
    return program;
}

}  // namespace

GlHandle build_program(const GlApi& gl, const std::vector<std::string>& files) {
    std::vector<AssembledShader> sources;
    for (const std::string& f : files) sources.push_back(assemble_shader(f));
    return link_program(gl, files, sources);
}

GlHandle build_program_from_text(const GlApi& gl, const std::vector<ShaderFile>& sources) {
    std::vector<std::string> files;
    std::vector<AssembledShader> assembled;
    for (const ShaderFile& f : sources) {
        files.push_back(f.name);
        assembled.push_back(assemble_shader(f));
    }
    return link_program(gl, files, assembled);
}

GlHandle make_buffer(const GlApi& gl, const void* data, std::size_t bytes, GLenum usage) {
    GLuint id = 0;
    gl.CreateBuffers(1, &id);
    gl.NamedBufferData(id, GLsizeiptr(bytes), data, usage);
    return GlHandle(gl, id, [](const GlApi& g, GLuint i) { g.DeleteBuffers(1, &i); });
}

GlHandle make_vertex_array(const GlApi& gl) {
    GLuint id = 0;
    gl.CreateVertexArrays(1, &id);
    return GlHandle(gl, id, [](const GlApi& g, GLuint i) { g.DeleteVertexArrays(1, &i); });
}

GlHandle make_texture(const GlApi& gl, GLenum internal_format, int width, int height) {
    GLuint id = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &id);
    gl.TextureStorage2D(id, 1, internal_format, width, height);
    gl.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return GlHandle(gl, id, [](const GlApi& g, GLuint i) { g.DeleteTextures(1, &i); });
}

GlHandle make_framebuffer(const GlApi& gl, const std::vector<GLuint>& colour, GLuint depth,
                          const std::string& name) {
    GLuint id = 0;
    gl.CreateFramebuffers(1, &id);
    GlHandle fb(gl, id, [](const GlApi& g, GLuint i) { g.DeleteFramebuffers(1, &i); });
    std::vector<GLenum> bufs;
    for (std::size_t i = 0; i < colour.size(); ++i) {
        gl.NamedFramebufferTexture(id, GLenum(GL_COLOR_ATTACHMENT0 + i), colour[i], 0);
        bufs.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    }
    if (depth) gl.NamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth, 0);
    gl.NamedFramebufferDrawBuffers(id, GLsizei(bufs.size()), bufs.data());
    if (gl.CheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("render", name, "framebuffer incomplete", ExitCode::internal);
    return fb;
}

GpuTimer::GpuTimer(const GlApi& gl) : gl_(&gl) {
    GLuint id = 0;
    gl.CreateQueries(GL_TIME_ELAPSED, 1, &id);
    query_ = GlHandle(gl, id, [](const GlApi& g, GLuint i) { g.DeleteQueries(1, &i); });
}
// glFinish around the query: llvmpipe runs commands lazily at the next flush, so without it a
// pass's work would be timed in whichever later pass first needs its results. On a GPU the query
// still measures GPU time; the finish only serialises passes, as the paper's per-pass table needs.
// llvmpipe's queries also miss work done inside the draw call (vertex and tessellation stages run
// there), so the pass time is the larger of the query and the wall time between the finishes.
// Untimed (GlApi::timed false), none of this runs: no finish, no query, 0 ms.
void GpuTimer::begin() {
    if (!gl_->timed) return;
    gl_->Finish();
    gl_->BeginQuery(GL_TIME_ELAPSED, query_.id());
    start_ = std::chrono::steady_clock::now();
}
void GpuTimer::end() {
    if (!gl_->timed) return;
    gl_->Finish();
    wall_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    gl_->EndQuery(GL_TIME_ELAPSED);
}
double GpuTimer::milliseconds() {
    if (!gl_->timed) return 0.0;
    GLuint64 ns = 0;
    gl_->GetQueryObjectui64v(query_.id(), GL_QUERY_RESULT, &ns);
    return std::max(double(ns) * 1e-6, wall_ms_);
}

GLint uniform_location(const GlApi& gl, GLuint program, const char* name) {
    return gl.GetUniformLocation(program, name);
}

void set_camera_uniforms(const GlApi& gl, GLuint program, const Camera& camera) {
    const glm::dvec3 d = direction_from_angles(camera.azimuth, camera.altitude);
    const bool ortho = is_orthographic(camera);
    gl.Uniform3f(gl.GetUniformLocation(program, "u_eye"), float(camera.eye.x), float(camera.eye.y), float(camera.eye.z));
    gl.Uniform4f(gl.GetUniformLocation(program, "u_view"), float(d.x), float(d.y), float(d.z), ortho ? 1.0f : 0.0f);
    gl.Uniform2f(gl.GetUniformLocation(program, "u_footprint"), ortho ? 0.0f : float(world_per_pixel(camera, 1.0)),
                 ortho ? float(world_per_pixel(camera, 1.0)) : 0.0f);
}

}  // namespace penink
