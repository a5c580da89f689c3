// TFT / AFT passes (Mower, "Fast Image-Space Silhouette Extraction"): the PN-triangle surface (tessellated in TCS/TES, level from the
// projected edge length) rendered into two R32F eye-distance textures (metres; PENINK_FAR = 1e30
// where no fragment): the nearest toward-facing and the nearest away-facing fragment per pixel.
// Combined mode does both in one geometry pass (gl_FrontFacing + MIN blending, same result);
// separate mode runs TFT and AFT as two culled, depth-tested passes, as in the paper's Table 3.
#pragma once
#include "core/camera.hpp"
#include "render/gl_objects.hpp"
#include "render/surface_geometry.hpp"

namespace penink {

struct TessellationOptions {
    float target_edge_px = 8.0f;  // tessellate until edges are about this long on screen
    int max_level = 16;           // 1 = flat triangles (no refinement)
    bool cull_patches = true;     // skip patches whose control hull is outside the frustum
    // One level per patch (its longest edge's) on all three edges, as a per-patch adaptive
    // tessellation does: neighbouring patches then disagree on a shared edge, which opens
    // T-junction cracks (the case Mower's Adjacency algorithm must handle). Off: each edge's level
    // depends on its end points only and neighbours agree.
    bool per_patch_level = false;
};

// Sets the PN tessellation uniforms of `program` (tft_aft.tesc/.tese: view-projection, viewport,
// levels, culling, eye) for a width x height target; the program is made current.
void set_tessellation_uniforms(const GlApi& gl, GLuint program, const Camera& camera, const TessellationOptions& tess,
                               int width, int height);

struct TftAftTimes {
    double tft_ms = 0.0, aft_ms = 0.0;  // combined mode puts the whole pass in tft_ms
};

class TftAftPass {
public:
    TftAftPass(const GlApi& gl, int width, int height);
    TftAftTimes draw(const SurfaceGeometry& surface, const Camera& camera,
                     const TessellationOptions& tess, bool separate_passes);
    GLuint toward_texture() const { return toward_.id(); }
    GLuint away_texture() const { return away_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    void set_uniforms(const Camera& camera, const TessellationOptions& tess, int mode) const;
    const GlApi* gl_;
    int width_, height_;
    GlHandle program_, toward_, away_, depth_, combined_fb_, toward_fb_, away_fb_;
    GpuTimer tft_timer_, aft_timer_;
};

}  // namespace penink
