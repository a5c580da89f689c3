#include "render/gl_library.hpp"

#include <dlfcn.h>

#include "core/error.hpp"

namespace penink {

SharedLibrary::SharedLibrary(std::initializer_list<const char*> names) {
    std::string why;
    for (const char* n : names) {
        name_ = n;
        if ((handle_ = ::dlopen(n, RTLD_NOW | RTLD_LOCAL))) return;
        if (const char* e = ::dlerror(); e && why.empty()) why = e;
    }
    name_ = *names.begin();
    throw Error("render", name_, "cannot load the OpenGL library (" + why + ")", ExitCode::internal);
}

SharedLibrary::~SharedLibrary() { ::dlclose(handle_); }

void* SharedLibrary::symbol(const char* name) const {
    void* p = ::dlsym(handle_, name);
    if (!p) throw Error("render", name_, std::string("has no ") + name, ExitCode::internal);
    return p;
}

OsMesaLibrary::OsMesaLibrary() {
    lib.get(CreateContextAttribs, "OSMesaCreateContextAttribs");
    lib.get(MakeCurrent, "OSMesaMakeCurrent");
    lib.get(DestroyContext, "OSMesaDestroyContext");
    lib.get(GetProcAddress, "OSMesaGetProcAddress");
}

#ifdef PENINK_HAVE_EGL
EglLibrary::EglLibrary() {
    lib.get(GetProcAddress, "eglGetProcAddress");
    lib.get(GetDisplay, "eglGetDisplay");
    lib.get(Initialize, "eglInitialize");
    lib.get(Terminate, "eglTerminate");
    lib.get(BindAPI, "eglBindAPI");
    lib.get(QueryString, "eglQueryString");
    lib.get(ChooseConfig, "eglChooseConfig");
    lib.get(CreateContext, "eglCreateContext");
    lib.get(DestroyContext, "eglDestroyContext");
    lib.get(MakeCurrent, "eglMakeCurrent");
}
#endif

}  // namespace penink
