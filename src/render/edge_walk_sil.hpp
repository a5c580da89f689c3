// Edge-walk SIL pass (`[silhouettes] method = "edge-walk"`): penink's contour-edge method built on the facet adjacencies
// of Mower, "Fast Image-Space Silhouette Extraction", 3.1 (the paper's own pixel test is render/id_adjacency_sil.hpp), beside Toward/Away: after the TFT/AFT pass has written the
// nearest toward/away eye distances, a second geometry pass (same PN tessellation program plus a
// geometry stage) stores every tessellated triangle (eye-relative corners, metres, and its facing)
// in an SSBO and the ID of the nearest toward- and away-facing triangle of each pixel in a
// second SSBO; a full-screen pass finds, for each pixel's visible toward triangle, the away
// triangles in its 5x5 neighbourhood that share a 3-space edge with it (crack-tolerant) and
// appends those silhouette edges to an edge SSBO; a GL_LINES pass draws them, tested against the
// TFT distances, into an R8 mask like SilPass (1 = silhouette), same size. Triangle and edge
// buffers grow to the frame's counts (the frame is redrawn when one overflows).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/camera.hpp"
#include "render/gl_objects.hpp"
#include "render/surface_geometry.hpp"
#include "render/tft_aft.hpp"

namespace penink {

struct EdgeWalkOptions {
    float tolerance = 1.0e-3f;        // relative to the longest triangle edge: edges this close are shared
    int radius = 2;                   // pixels: away IDs searched in a (2 radius + 1)^2 window
    int walk_rounds = 32;             // contour walk rounds (0 = only the edges found on the raster)
    float depth_tolerance = 1.0e-4f;  // relative: an edge fragment this far behind the TFT is visible
};

struct EdgeWalkTimes {
    double ids_ms = 0, detect_ms = 0, walk_ms = 0, lines_ms = 0;  // GPU ms of the passes (walk: all rounds)
};

class EdgeWalkSilPass {
public:
    EdgeWalkSilPass(const GlApi& gl, int width, int height);
    EdgeWalkTimes draw(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                        GLuint toward_texture, GLuint away_texture, const EdgeWalkOptions& options = {});
    GLuint silhouette_texture() const { return mask_.id(); }
    std::size_t triangle_count() const { return triangles_; }  // tessellated triangles last frame
    std::size_t edge_count() const { return edges_; }          // silhouette edges found last frame
    // Per-pixel nearest toward / away triangle IDs (0 = none), row 0 = top, for tests.
    void read_ids(std::vector<std::uint32_t>& toward, std::vector<std::uint32_t>& away) const;

    // The last frame's triangles: 3 eye-relative corners each (metres); w of the first corner is
    // 1 for toward-facing, 0 for away-facing. Index = ID - 1.
    std::vector<glm::vec4> read_triangles() const;
    // The last frame's silhouette edges: 2 eye-relative end points each (metres).
    std::vector<glm::vec4> read_edges() const;

private:
    double draw_ids(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                    GLuint toward_texture, GLuint away_texture);
    double detect(GLuint toward_texture, GLuint away_texture, const EdgeWalkOptions& options);
    double walk(const EdgeWalkOptions& options);
    double draw_lines(const Camera& camera, GLuint toward_texture, const EdgeWalkOptions& options);
    void reset_buffers();
    void set_hash_uniforms(GLuint program) const;
    // Hash uniforms, the TFT/AFT textures and the counter/triangle/ID/flag buffers of a frame.
    void bind_frame_inputs(GLuint program, GLuint toward_texture, GLuint away_texture) const;
    bool grow_on_overflow();
    const GlApi* gl_;
    int width_, height_;
    GlHandle id_program_, detect_program_, walk_program_, line_program_, mask_, fb_, empty_vao_;
    GlHandle counter_, triangles_buf_, flags_buf_, edges_buf_, table_buf_, pixel_ids_;
    std::size_t capacity_ = 0, edge_capacity_ = 0, table_size_ = 0, triangles_ = 0, edges_ = 0;
    float cell_ = 1.0f;  // metres: edge hash cell, from the camera's far plane
    GpuTimer ids_timer_, detect_timer_, walk_timer_, lines_timer_;
};

}  // namespace penink
