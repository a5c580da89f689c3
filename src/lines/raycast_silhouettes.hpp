// Reference silhouettes of a PN-triangle surface (Vlachos et al. 2001) by ray casting, independent
// of the silhouette methods it scores (Toward/Away and Adjacency look at facing, object-space at
// the facing of tessellated edges; this looks only at where the first hit jumps): given the surface
// as triangles (in practice its CPU PN tessellation with edges well under a pixel:
// scene/raycast_reference.hpp), one ray per sample of a grid `supersample` times finer than the image (sample (i, j) through
// image point ((i + 0.5) / s, (j + 0.5) / s)), each intersected exactly (Moller & Trumbore 1997)
// with the triangles whose screen bounding box covers it, nearest hit kept (eye distance, metres).
// Two 4-neighbour samples are split by a silhouette when the farther one sees no surface, or when
// its eye distance exceeds the nearer one's by more than a continuous surface through both could
// give: 4 x the step between neighbouring rays on the farther sample's plane (d * dalpha * tan psi,
// psi between ray and normal, capped at 89 deg) and at least `min_gap` relative. Splits whose near
// sample lies on a triangle flagged `cut` (at the DEM's cut edges) are not silhouettes. The
// splits are joined by marching squares over the sample grid (a point midway between the two
// samples of each split): image polylines in pixels (origin top-left, y down), 2 points each.
// Cost: O(samples + triangles x covered samples); rows are split over the cores; memory 8 bytes
// per sample plus a screen box per triangle.
#pragma once
#include <vector>

#include <glm/vec2.hpp>

#include <cstdint>

#include <glm/vec3.hpp>

#include "core/camera.hpp"

namespace penink {

struct RaycastOptions {
    int supersample = 4;     // samples per image pixel along x and y (>= 1)
    double min_gap = 1e-3;   // smallest relative eye-distance jump taken as a silhouette
};

// pos: world vertices; tri: triangles (either facing); cut: one flag per triangle (may be empty).
std::vector<std::vector<glm::vec2>> raycast_silhouettes(const std::vector<glm::vec3>& pos,
                                                        const std::vector<glm::uvec3>& tri,
                                                        const std::vector<std::uint8_t>& cut, const Camera& camera,
                                                        const RaycastOptions& options = {});

}  // namespace penink
