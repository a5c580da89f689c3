// Both context back-ends give OpenGL 4.5 core: OSMesa, and EGL (here through Mesa's surfaceless
// llvmpipe; on a GPU machine through its EGL device). Unknown back-end names are errors.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "render/gl_context.hpp"
#include "render/gl_library.hpp"

using namespace penink;

TEST(GlContext, EglGivesOpenGl45Core) {
    const auto ctx = make_gl_context(GlBackend::egl);
    EXPECT_EQ(ctx->backend(), GlBackend::egl);
    EXPECT_EQ(ctx->description().rfind("EGL: ", 0), 0u) << ctx->description();
    EXPECT_NE(ctx->description().find("OpenGL 4.5"), std::string::npos) << ctx->description();
    GLint major = 0, minor = 0;
    ctx->gl().GetIntegerv(GL_MAJOR_VERSION, &major);
    ctx->gl().GetIntegerv(GL_MINOR_VERSION, &minor);
    EXPECT_GE(major * 10 + minor, 45);
}

TEST(GlContext, BackendNames) {
    EXPECT_EQ(parse_gl_backend("osmesa"), GlBackend::osmesa);
    EXPECT_EQ(parse_gl_backend("egl"), GlBackend::egl);
    try {
        parse_gl_backend("vulkan");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: render: unknown OpenGL backend \"vulkan\" (use osmesa or egl)");
    }
}

// The GL libraries are opened at context creation (gl_library.hpp): a library that does not load
// and a symbol it lacks are errors naming the library.
TEST(GlContext, LibraryAndSymbolErrorsNameTheLibrary) {
    try {
        SharedLibrary missing({"libpenink-no-such-gl.so.9"});
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: render: libpenink-no-such-gl.so.9: cannot load the OpenGL library "
                               "(libpenink-no-such-gl.so.9: cannot open shared object file: No such file or directory)");
    }
    const OsMesaLibrary osmesa;
    EXPECT_NE(osmesa.GetProcAddress, nullptr);
    try {
        osmesa.lib.symbol("OSMesaNoSuchEntryPoint");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: render: libOSMesa.so.8: has no OSMesaNoSuchEntryPoint");
    }
}
