#include "render/gl_api.hpp"

#include "core/error.hpp"

namespace penink {

GlApi load_gl_api(const GlProcLoader& loader) {
    GlApi gl;
#define PENINK_GL_LOAD(type, name)                                                           \
    gl.name = reinterpret_cast<type>(loader("gl" #name));                                    \
    if (!gl.name)                                                                            \
        throw Error("render", "", "OpenGL function gl" #name " is not available",           \
                    ExitCode::internal);
    PENINK_GL_FUNCTIONS(PENINK_GL_LOAD)
#undef PENINK_GL_LOAD
    return gl;
}

namespace {
const char* gl_error_name(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return "GL error";
    }
}
}  // namespace

void check_gl_error(const GlApi& gl, const std::string& where) {
    std::string errors;
    for (int i = 0; i < 16; ++i) {
        const GLenum e = gl.GetError();
        if (e == GL_NO_ERROR) break;
        errors += (errors.empty() ? "" : ", ") + std::string(gl_error_name(e));
    }
    if (!errors.empty()) throw Error("render", where, "OpenGL error " + errors, ExitCode::internal);
}

}  // namespace penink
