// GPU copy of a SurfaceMesh for the PN-triangle passes: interleaved position + vertex normal
// (world frame, float) and the triangle index list drawn as 3-vertex GL_PATCHES.
#pragma once
#include "render/gl_objects.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

class SurfaceGeometry {
public:
    SurfaceGeometry(const GlApi& gl, const SurfaceMesh& mesh);
    // Binds the vertex array and issues the patch draw (caller has bound a tessellation program).
    void draw_patches() const;
    std::size_t triangle_count() const { return triangles_; }

private:
    const GlApi* gl_;
    GlHandle vertices_, indices_, vao_;
    std::size_t triangles_ = 0;
};

}  // namespace penink
