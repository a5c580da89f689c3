#include "support/pn_eval.hpp"

#include <algorithm>
#include <string>

#include <glm/vec4.hpp>

#include "core/error.hpp"
#include "render/gl_objects.hpp"
#include "render/shader_source.hpp"

namespace penink {

// tests/support/shaders/*.glsl, embedded at build time by cmake/embed_files.cmake.
const std::vector<ShaderFile>& test_support_shaders();

namespace {

GlHandle pn_eval_program(const GlApi& gl) {
    for (const ShaderFile& f : test_support_shaders())
        if (std::string(f.name) == "pn_eval.comp.glsl") return build_program_from_text(gl, {f});
    throw Error("render", "pn_eval.comp.glsl", "not embedded in the test-support library", ExitCode::internal);
}

}  // namespace

std::vector<PnSample> evaluate_pn_on_gpu(const GlApi& gl, const std::vector<PnQuery>& queries) {
    std::vector<glm::vec4> packed;  // std430 layout of PnQuery in the shader: 7 vec4
    packed.reserve(queries.size() * 7);
    for (const PnQuery& q : queries) {
        for (const glm::vec3& p : q.p) packed.emplace_back(p, 1.0f);
        for (const glm::vec3& n : q.n) packed.emplace_back(n, 0.0f);
        packed.emplace_back(q.bary, 0.0f);
    }
    const std::size_t count = queries.size();
    const GlHandle program = pn_eval_program(gl);
    const GlHandle in = make_buffer(gl, packed.data(), std::max<std::size_t>(1, packed.size()) * sizeof(glm::vec4));
    const GlHandle out = make_buffer(gl, nullptr, std::max<std::size_t>(1, count * 2) * sizeof(glm::vec4), GL_DYNAMIC_READ);
    gl.UseProgram(program.id());
    gl.Uniform1ui(uniform_location(gl, program.id(), "u_count"), GLuint(count));
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    gl.DispatchCompute(GLuint((count + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> raw(count * 2);
    gl.GetNamedBufferSubData(out.id(), 0, GLsizeiptr(raw.size() * sizeof(glm::vec4)), raw.data());
    check_gl_error(gl, "PN evaluation pass");
    std::vector<PnSample> samples(count);
    for (std::size_t i = 0; i < count; ++i) samples[i] = {glm::vec3(raw[2 * i]), glm::vec3(raw[2 * i + 1])};
    return samples;
}

}  // namespace penink
