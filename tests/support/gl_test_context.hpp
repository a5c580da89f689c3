// The GL context of the GPU tests (render, scene): one OSMesa (software, offscreen) context per
// test binary run, created on first use and made current again on every call.
#pragma once
#include <memory>

#include "render/gl_context.hpp"

namespace penink::test {

inline GlContext& test_context() {
    static std::unique_ptr<GlContext> ctx = make_gl_context(GlBackend::osmesa);
    ctx->make_current();  // another test may have made its own context current
    return *ctx;
}

}  // namespace penink::test
