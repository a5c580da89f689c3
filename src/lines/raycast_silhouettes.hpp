// Reference silhouettes of a PN-triangle surface (Vlachos et al. 2001) by ray casting, independent
// of the silhouette methods it scores (Toward/Away and Adjacency look at facing, object-space at
// the facing of tessellated edges; this looks only at where the first hit jumps): the surface
// tessellated on the CPU to edges of about `edge_px` image pixels (surface/pn_tessellation.hpp),
// one ray per sample of a grid `supersample` times finer than the image (sample (i, j) through
// image point ((i + 0.5) / s, (j + 0.5) / s)), each intersected exactly (Moller & Trumbore 1997)
// with the triangles whose screen bounding box covers it, nearest hit kept (eye distance, metres).
// Two 4-neighbour samples are split by a silhouette when the farther one sees no surface, or when
// its eye distance exceeds the nearer one's by more than a continuous surface through both could
// give: 4 x the step between neighbouring rays on the farther sample's plane (d * dalpha * tan psi,
// psi between ray and normal, capped at 89 deg) and at least `min_gap` relative. Splits whose near
// sample lies on a patch at the mesh boundary (the DEM's cut edges) are not silhouettes. The
// splits are joined by marching squares over the sample grid (a point midway between the two
// samples of each split): image polylines in pixels (origin top-left, y down), 2 points each.
// Cost: O(samples + triangles x covered samples); rows are split over the cores; memory 8 bytes
// per sample plus the tessellation.
#pragma once
#include <vector>

#include <glm/vec2.hpp>

#include "core/camera.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

struct RaycastOptions {
    int supersample = 4;     // samples per image pixel along x and y (>= 1)
    float edge_px = 0.5f;    // tessellated edge length, image pixels
    int max_level = 64;      // tessellation level cap (OpenGL's maximum)
    double min_gap = 1e-3;   // smallest relative eye-distance jump taken as a silhouette
};

std::vector<std::vector<glm::vec2>> raycast_silhouettes(const SurfaceMesh& mesh, const Camera& camera,
                                                        const RaycastOptions& options = {});

}  // namespace penink
