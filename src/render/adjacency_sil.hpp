// Adjacency SIL pass (seed 001, 3.1), beside Toward/Away: after the TFT/AFT pass has written the
// nearest toward/away eye distances, a second geometry pass (same PN tessellation program plus a
// geometry stage) stores every tessellated triangle (eye-relative corners, metres, and its facing)
// in an SSBO and the ID of the nearest toward- and away-facing triangle of each pixel in a
// second SSBO; a full-screen pass then marks the pixels where the visible toward triangle touches
// a neighbouring pixel's away triangle in 3-space and their contact projects onto the pixel (see
// shaders/adjacency_sil.detect.frag.glsl for the crack tolerance). Output: an R8 mask like
// SilPass (1 = silhouette), same size. The triangle buffer grows to the frame's count and the
// frame is redrawn when it overflows.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/camera.hpp"
#include "render/gl_objects.hpp"
#include "render/surface_geometry.hpp"
#include "render/tft_aft.hpp"

namespace penink {

struct AdjacencyOptions {
    float tolerance = 1.0e-3f;  // relative to the longest triangle edge: corners closer touch
    float half_width = 0.71f;   // pixels: the contact must pass this close to the pixel centre
};

struct AdjacencyTimes {
    double ids_ms = 0, detect_ms = 0;  // GPU ms of the triangle-ID pass and the detection pass
};

class AdjacencySilPass {
public:
    AdjacencySilPass(const GlApi& gl, int width, int height);
    AdjacencyTimes draw(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                        GLuint toward_texture, GLuint away_texture, const AdjacencyOptions& options = {});
    GLuint silhouette_texture() const { return mask_.id(); }
    std::size_t triangle_count() const { return triangles_; }  // tessellated triangles last frame
    // Per-pixel nearest toward / away triangle IDs (0 = none), row 0 = top, for tests.
    void read_ids(std::vector<std::uint32_t>& toward, std::vector<std::uint32_t>& away) const;

    // The last frame's triangles: 3 eye-relative corners each (metres); w of the first corner is
    // 1 for toward-facing, 0 for away-facing. Index = ID - 1.
    std::vector<glm::vec4> read_triangles() const;

private:
    double draw_ids(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                    GLuint toward_texture, GLuint away_texture);
    double detect(const Camera& camera, GLuint toward_texture, GLuint away_texture, const AdjacencyOptions& options);
    void reset_buffers();
    const GlApi* gl_;
    int width_, height_;
    GlHandle id_program_, detect_program_, mask_, fb_, empty_vao_;
    GlHandle counter_, triangles_buf_, pixel_ids_;
    std::size_t capacity_ = 0, triangles_ = 0;
    GpuTimer ids_timer_, detect_timer_;
};

}  // namespace penink
