// Adjacency SIL pass, the paper's algorithm (Mower, "Fast Image-Space Silhouette Extraction",
// 3.1; `[silhouettes] method = "adjacency"`). After the TFT/AFT pass:
// 1. ID pass: the same PN tessellation program plus a geometry stage renders every tessellated
//    triangle, depth-tested, into an R32UI triangle-ID raster (0 = no surface) and appends its
//    three world vertices (local metres) to a triangle list in an SSBO (index = ID - 1; the
//    geometry stage stands in for the paper's transform feedback).
// 2. Pixel pass: pixel p (triangle a) is a silhouette pixel when one of its 4 neighbours q holds
//    no surface (sky), or a triangle b != a that lies farther from the eye (p is on the occluding
//    side) and is not adjacent to a in 3-space: a and b share no pair of world vertices (the
//    paper's shared edge; equal within float rounding, 1e-5 of the eye distance), nor, with
//    `vertex_adjacency`, one vertex, nor, with crack handling, touch in a T-junction (a vertex of
//    one within `crack_tolerance` x an edge's length of that edge of the other; patches of
//    different tessellation levels meet that way). The T-junction test is our reading of the
//    paper's crack case; its text was not at hand. penink adds one condition unless
//    `mesh_borders`: the surface turns away at p (an away fragment behind p's at p or an
//    8-neighbour, as Toward/Away), so the DEM's cut edges and hole rims, whose triangles are not
//    adjacent to what lies beyond them either, are left to the outline as for the other methods,
//    while skylines and contours (a back-facing fold behind the front sheet) stay.
// Output: an R8 mask, width x height, 1 = silhouette (like SilPass), traced by src/lines.
// 4 neighbours, not 8: every boundary between two triangles' pixel regions has a 4-neighbour
// pair across it, so 4 find every boundary with half the triangle-pair tests, and marking the
// near side of 4-neighbour pairs gives an 8-connected line one pixel wide, as the tracer wants.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/camera.hpp"
#include "render/gl_objects.hpp"
#include "render/surface_geometry.hpp"
#include "render/tft_aft.hpp"

namespace penink {

struct IdAdjacencyOptions {
    // Relative to an edge's length: a vertex of one triangle this close to an edge of another
    // makes them T-junction neighbours (0: no crack handling). Covers the chord-to-cubic offset of
    // a PN edge split at different levels (0.03 already removes most, tests/render).
    float crack_tolerance = 0.1f;
    // true: the paper's ID test alone, mesh borders (cut edges, hole rims) are silhouettes too.
    bool mesh_borders = false;
    // true: triangles with one common vertex are adjacent too. A one-pixel step near a vertex
    // often crosses between two triangles of its fan that share only that vertex: with the
    // paper's edge test alone (false) about a third of all triangle boundaries inside a smooth
    // surface tessellated to 4 px were marked (tests/render/id_adjacency_sil_test.cpp).
    bool vertex_adjacency = true;
};

struct IdAdjacencyTimes {
    double ids_ms = 0, pixels_ms = 0;  // GPU ms of the ID pass (all attempts) and the pixel pass
};

class IdAdjacencySilPass {
public:
    IdAdjacencySilPass(const GlApi& gl, int width, int height);
    IdAdjacencyTimes draw(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess,
                          GLuint toward_texture, GLuint away_texture, const IdAdjacencyOptions& options = {});
    GLuint silhouette_texture() const { return mask_.id(); }
    std::size_t triangle_count() const { return triangles_; }  // tessellated triangles last frame
    // The last frame's ID raster (0 = none), row 0 = top, for tests.
    std::vector<std::uint32_t> read_ids() const;
    // The last frame's triangle list: 3 world corners each (w unused), index = ID - 1.
    std::vector<glm::vec4> read_triangles() const;

private:
    double draw_ids(const SurfaceGeometry& surface, const Camera& camera, const TessellationOptions& tess);
    double mark_pixels(GLuint toward_texture, GLuint away_texture, const IdAdjacencyOptions& options);
    const GlApi* gl_;
    int width_, height_;
    GlHandle id_program_, pixel_program_, ids_, depth_, id_fb_, mask_, mask_fb_, empty_vao_, counter_, triangles_buf_;
    std::size_t capacity_ = 0, triangles_ = 0;
    GpuTimer ids_timer_, pixels_timer_;
};

}  // namespace penink
