// The speed/accuracy chart's reference for a real DEM: the PN-triangle surface (Vlachos et al.
// 2001) tessellated on the CPU to edges of about `edge_px` image pixels (surface/pn_tessellation.hpp,
// level cap 64), then ray cast at `supersample` x the image resolution with silhouettes where the
// first hit jumps (lines/raycast_silhouettes.hpp). Tessellated triangles of patches with a vertex on
// the mesh boundary are flagged as cut edges. Image polylines in pixels (origin top-left, y down).
#pragma once
#include <vector>

#include <glm/vec2.hpp>

#include "core/camera.hpp"
#include "lines/raycast_silhouettes.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

struct RaycastReferenceOptions {
    RaycastOptions rays;   // supersampling (>= 4 for the chart) and the smallest jump
    float edge_px = 0.5f;  // tessellated edge length, image pixels
};

std::vector<std::vector<glm::vec2>> raycast_reference(const SurfaceMesh& mesh, const Camera& camera,
                                                      const RaycastReferenceOptions& options = {});

}  // namespace penink
