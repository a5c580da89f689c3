#include "render/gl_context.hpp"

#include <vector>

#include "core/error.hpp"
#include "render/gl_library.hpp"

namespace penink {

std::string GlContext::describe(const char* backend_name) const {
    const auto str = [&](GLenum e) {
        const GLubyte* s = gl_.GetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return std::string(backend_name) + ": " + str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

void GlContext::init_api(const GlProcLoader& loader) {
    gl_ = load_gl_api(loader);
    // First timer query of a context returns garbage on llvmpipe: issue a throwaway one.
    GLuint q = 0;
    gl_.CreateQueries(GL_TIME_ELAPSED, 1, &q);
    gl_.BeginQuery(GL_TIME_ELAPSED, q);
    gl_.EndQuery(GL_TIME_ELAPSED);
    GLuint64 ns = 0;
    gl_.GetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
    gl_.DeleteQueries(1, &q);
    check_gl_error(gl_, "context creation");
}

namespace {

class OsMesaContext final : public GlContext {
public:
    OsMesaContext() {
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                               OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
        ctx_ = os_.CreateContextAttribs(attribs, nullptr);
        if (!ctx_) throw Error("render", "", "cannot create an OpenGL 4.5 core context with OSMesa",
                               ExitCode::internal);
        if (!os_.MakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
            os_.DestroyContext(ctx_);
            throw Error("render", "", "cannot make the OSMesa context current", ExitCode::internal);
        }
        init_api([this](const char* name) { return reinterpret_cast<void*>(os_.GetProcAddress(name)); });
    }
    ~OsMesaContext() override { os_.DestroyContext(ctx_); }
    std::string description() const override { return describe("OSMesa"); }
    void make_current() override { os_.MakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1); }
    GlBackend backend() const override { return GlBackend::osmesa; }

private:
    OsMesaLibrary os_;  // first member: loaded before, closed after the context
    OSMesaContext ctx_ = nullptr;
    std::vector<unsigned char> buffer_ = std::vector<unsigned char>(4);
};

#ifdef PENINK_HAVE_EGL
class EglContext final : public GlContext {
public:
    EglContext() {
        display_ = headless_display();
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !egl_.Initialize(display_, &major, &minor))
            fail("cannot initialise an EGL display");
        egl_.BindAPI(EGL_OPENGL_API);
        const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        ctx_ = egl_.CreateContext(display_, context_config(), EGL_NO_CONTEXT, ctx_attribs);
        if (ctx_ == EGL_NO_CONTEXT) fail("cannot create an OpenGL 4.5 core context with EGL");
        if (!egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_))
            fail("cannot make the EGL context current (surfaceless)");
        init_api([this](const char* name) { return reinterpret_cast<void*>(egl_.GetProcAddress(name)); });
    }
    ~EglContext() override {
        egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (ctx_ != EGL_NO_CONTEXT) egl_.DestroyContext(display_, ctx_);
        egl_.Terminate(display_);
    }
    std::string description() const override { return describe("EGL"); }
    void make_current() override { egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_); }
    GlBackend backend() const override { return GlBackend::egl; }

private:
    // A display with no window system: the first EGL device (a GPU, EGL_EXT_platform_device),
    // else Mesa's surfaceless platform, else the default display.
    EGLDisplay headless_display() const {
        const auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl_.GetProcAddress("eglQueryDevicesEXT"));
        const auto platform_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl_.GetProcAddress("eglGetPlatformDisplayEXT"));
        if (query_devices && platform_display) {
            EGLDeviceEXT devices[8];
            EGLint count = 0;
            if (query_devices(8, devices, &count) && count > 0) {
                const EGLDisplay d = platform_display(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
                if (d != EGL_NO_DISPLAY) return d;
            }
        }
        if (platform_display) {
            const EGLDisplay d = platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (d != EGL_NO_DISPLAY) return d;
        }
        return egl_.GetDisplay(EGL_DEFAULT_DISPLAY);
    }
    // No config is needed to render into framebuffer objects (EGL_KHR_no_config_context); older
    // drivers get any desktop-GL config.
    EGLConfig context_config() {
        const char* ext = egl_.QueryString(display_, EGL_EXTENSIONS);
        if (ext && std::string(ext).find("EGL_KHR_no_config_context") != std::string::npos) return EGL_NO_CONFIG_KHR;
        const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config;
        EGLint count = 0;
        if (!egl_.ChooseConfig(display_, attribs, &config, 1, &count) || count < 1)
            fail("no EGL config with desktop OpenGL");
        return config;
    }
    [[noreturn]] void fail(const char* what) {
        if (display_ != EGL_NO_DISPLAY) egl_.Terminate(display_);
        throw Error("render", "", what, ExitCode::internal);
    }
    EglLibrary egl_;  // first member: loaded before, closed after the display
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext ctx_ = EGL_NO_CONTEXT;
};
#endif

}  // namespace

GlBackend parse_gl_backend(const std::string& name) {
    if (name == "osmesa") return GlBackend::osmesa;
    if (name == "egl") return GlBackend::egl;
    throw Error("render", "", "unknown OpenGL backend \"" + name + "\" (use osmesa or egl)");
}

std::unique_ptr<GlContext> make_gl_context(GlBackend backend) {
#ifdef PENINK_HAVE_EGL
    if (backend == GlBackend::egl) return std::make_unique<EglContext>();
#else
    if (backend == GlBackend::egl)
        throw Error("render", "", "this build has no EGL support", ExitCode::internal);
#endif
    return std::make_unique<OsMesaContext>();
}

}  // namespace penink
