// Headless OpenGL 4.5 core contexts behind one small interface: OSMesa (software, llvmpipe; the
// default, needs no display or GPU) and EGL (surfaceless, for machines with a GPU). Rendering
// always goes to framebuffer objects, so the context's own drawable is a token 1x1 buffer.
#pragma once
#include <memory>
#include <string>

#include "render/gl_api.hpp"

namespace penink {

enum class GlBackend { osmesa, egl };

class GlContext {
public:
    virtual ~GlContext() = default;
    const GlApi& gl() const { return gl_; }
    virtual std::string description() const = 0;  // "OSMesa: llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6"
    virtual GlBackend backend() const = 0;
    // Makes this context current on the calling thread again (after another one was).
    virtual void make_current() = 0;
    // Turns the GPU timers of every pass made on this context on or off (GlApi::timed).
    void set_timed(bool on) { gl_.timed = on; }

protected:
    GlApi gl_;
    std::string describe(const char* backend_name) const;
    void init_api(const GlProcLoader& loader);
};

// Parses "osmesa" / "egl"; throws penink::Error(stage "render") otherwise.
GlBackend parse_gl_backend(const std::string& name);

// Makes the context current on this thread. Throws penink::Error(stage "render", exit code 1)
// with one line when no OpenGL 4.5 core context can be created.
std::unique_ptr<GlContext> make_gl_context(GlBackend backend = GlBackend::osmesa);

}  // namespace penink
