// The OpenGL 4.5 core entry points penink uses, as a table of function pointers loaded from the
// context's own GetProcAddress (OSMesa does not export every core function, e.g.
// glGetQueryObjectui64v). Owned by a GlContext; passes receive it as `const GlApi&`.
#pragma once
#include <functional>
#include <string>

#define GL_GLEXT_PROTOTYPES 0
#include <GL/glcorearb.h>

namespace penink {

#define PENINK_GL_FUNCTIONS(X)                                                                  \
    X(PFNGLGETERRORPROC, GetError)                                                              \
    X(PFNGLGETSTRINGPROC, GetString)                                                            \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                        \
    X(PFNGLENABLEPROC, Enable)                                                                  \
    X(PFNGLDISABLEPROC, Disable)                                                                \
    X(PFNGLVIEWPORTPROC, Viewport)                                                              \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                            \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                                            \
    X(PFNGLCULLFACEPROC, CullFace)                                                              \
    X(PFNGLBLENDEQUATIONPROC, BlendEquation)                                                    \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                                            \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                                    \
    X(PFNGLLINEWIDTHPROC, LineWidth)                                                            \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                                          \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                                          \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                        \
    X(PFNGLFINISHPROC, Finish)                                                                  \
    X(PFNGLCREATESHADERPROC, CreateShader)                                                      \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                      \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                                    \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                        \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                              \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                                      \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                    \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                                      \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                        \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                      \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                            \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                    \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                                          \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                          \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                                            \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                                            \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                                                            \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                                                            \
    X(PFNGLUNIFORM4FPROC, Uniform4f)                                                            \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui)                                                          \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                                \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                              \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                                          \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                          \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)                                \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)                              \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)                                \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)                                \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)                              \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                                    \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                    \
    X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                                                \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                                          \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                                  \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)                                    \
    X(PFNGLMAPNAMEDBUFFERRANGEPROC, MapNamedBufferRange)                                        \
    X(PFNGLUNMAPNAMEDBUFFERPROC, UnmapNamedBuffer)                                              \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                                                      \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                          \
    X(PFNGLPATCHPARAMETERIPROC, PatchParameteri)                                                \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                                                  \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                  \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                                              \
    X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                                            \
    X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                                                \
    X(PFNGLGETTEXTUREIMAGEPROC, GetTextureImage)                                                \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                                          \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                          \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)                                \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)                        \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)                        \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)                                \
    X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)                              \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                \
    X(PFNGLCREATEQUERIESPROC, CreateQueries)                                                    \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                                    \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                                                          \
    X(PFNGLENDQUERYPROC, EndQuery)                                                              \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                                        \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)

struct GlApi {
#define PENINK_GL_MEMBER(type, name) type name = nullptr;
    PENINK_GL_FUNCTIONS(PENINK_GL_MEMBER)
#undef PENINK_GL_MEMBER
    // Whether the passes' GpuTimers measure (gl_objects.hpp: a glFinish on each side of a pass and
    // a time query); false when no timing is asked for: the timers then cost nothing and read 0.
    bool timed = true;
};

using GlProcLoader = std::function<void*(const char* name)>;

// Loads every entry point; throws penink::Error(stage "render") naming the first one missing.
GlApi load_gl_api(const GlProcLoader& loader);

// Throws penink::Error(stage "render", file = where, ExitCode::internal) if glGetError reports
// anything (all pending errors are drained and named).
void check_gl_error(const GlApi& gl, const std::string& where);

}  // namespace penink
