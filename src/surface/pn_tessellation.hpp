// CPU tessellation of the PN-triangle surface (Vlachos et al. 2001) the GPU draws in
// shaders/tft_aft.{tesc,tese}.glsl: the same per-patch level rule (edge level = ceil(projected
// corner distance / target px) clamped to [1, max_level], inner = max of the outer levels, patches
// whose control hull lies outside one frustum plane culled) and OpenGL's triangle tessellation
// with equal_spacing (concentric rings of the unit triangle; the outer ring's edges subdivided by
// their own levels). Output: welded triangles (world frame, CCW like the patch, so facing agrees
// with gl_FrontFacing) and the PN normal per vertex. Vertices on a patch edge are keyed by the
// mesh edge and step, so neighbouring patches share them exactly (no cracks). The zipper filling
// of the outer ring is ours (the GL spec leaves it to the implementation); vertices match the GPU.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "surface/pn_triangle.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

struct PnLevels {
    std::array<int, 3> outer{1, 1, 1};  // outer[i]: edge opposite corner i (as gl_TessLevelOuter)
    int inner = 1;
    bool culled = false;
};

// Unit-triangle triangulation: barycentric points and CCW triangles; `edge[i]` is -1 for an
// interior point, 3 + c for corner c, or the side (0: corners 1-2, 1: 2-0, 2: 0-1) it lies on,
// with `step[i]` its index along that side counted from the side's lower corner.
struct BaryTriangulation {
    std::vector<glm::vec3> bary;
    std::vector<int> edge, step;
    std::vector<glm::uvec3> tri;
};

struct PnTessellation {
    std::vector<glm::vec3> pos;          // welded vertices, world frame
    std::vector<glm::vec3> normal;       // unit PN normal per vertex
    std::vector<glm::uvec3> tri;         // counter-clockwise (front = toward an eye above)
    std::vector<std::uint32_t> patch;    // source triangle of each tessellated triangle
};

// Levels of one patch with the GPU rule (float clip coordinates, as in the TCS).
PnLevels pn_patch_levels(const PnPatch& patch, const glm::mat4& view_proj, glm::vec2 viewport,
                         float target_edge_px, int max_level);

// OpenGL triangle tessellation, equal_spacing, of the given levels (levels clamped to [1, 64]).
BaryTriangulation tessellate_unit_triangle(const PnLevels& levels);

// Whole surface with the GPU's view-dependent levels.
PnTessellation tessellate_pn_surface(const SurfaceMesh& mesh, const glm::dmat4& view_proj,
                                     glm::vec2 viewport, float target_edge_px, int max_level);

// Whole surface at one uniform level for every patch (no culling).
PnTessellation tessellate_pn_surface_uniform(const SurfaceMesh& mesh, int level);

}  // namespace penink
