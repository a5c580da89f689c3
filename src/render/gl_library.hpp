// The OSMesa and EGL entry points penink calls, resolved with dlopen/dlsym when a context is made
// (libOSMesa.so.8, libEGL.so.1) instead of at program start: commands that draw nothing
// (`drainage`, `--help`) then start without Mesa's and LLVM's libraries (their relocations cost
// ≈ 17 ms of every start here) and run on machines without them. GL functions themselves come
// from the context's GetProcAddress (gl_api.hpp).
#pragma once
#include <string>

#include <GL/osmesa.h>
#ifdef PENINK_HAVE_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

namespace penink {

// One dlopen'ed library, closed with its owner. Throws penink::Error("render", name,
// "cannot load the OpenGL library (DLERROR)", internal) when none of `names` loads.
class SharedLibrary {
public:
    explicit SharedLibrary(std::initializer_list<const char*> names);
    ~SharedLibrary();
    SharedLibrary(const SharedLibrary&) = delete;
    SharedLibrary& operator=(const SharedLibrary&) = delete;
    // The symbol, or a penink::Error naming the library and the symbol when it is missing.
    void* symbol(const char* name) const;
    template <class F> void get(F& out, const char* name) const { out = reinterpret_cast<F>(symbol(name)); }

private:
    void* handle_ = nullptr;
    std::string name_;
};

struct OsMesaLibrary {
    SharedLibrary lib{"libOSMesa.so.8", "libOSMesa.so"};
    decltype(&OSMesaCreateContextAttribs) CreateContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) MakeCurrent = nullptr;
    decltype(&OSMesaDestroyContext) DestroyContext = nullptr;
    decltype(&OSMesaGetProcAddress) GetProcAddress = nullptr;
    OsMesaLibrary();
};

#ifdef PENINK_HAVE_EGL
struct EglLibrary {
    SharedLibrary lib{"libEGL.so.1", "libEGL.so"};
    decltype(&eglGetProcAddress) GetProcAddress = nullptr;
    decltype(&eglGetDisplay) GetDisplay = nullptr;
    decltype(&eglInitialize) Initialize = nullptr;
    decltype(&eglTerminate) Terminate = nullptr;
    decltype(&eglBindAPI) BindAPI = nullptr;
    decltype(&eglQueryString) QueryString = nullptr;
    decltype(&eglChooseConfig) ChooseConfig = nullptr;
    decltype(&eglCreateContext) CreateContext = nullptr;
    decltype(&eglDestroyContext) DestroyContext = nullptr;
    decltype(&eglMakeCurrent) MakeCurrent = nullptr;
    EglLibrary();
};
#endif

}  // namespace penink
