// Exact object-space silhouettes of a triangle surface (e.g. the CPU PN tessellation of
// surface/pn_tessellation.hpp, world frame) for a perspective camera (core/camera.hpp): the mesh
// edges whose two triangles face opposite ways (n . (eye - p) > 0 on one side only; n from the
// CCW winding, as gl_FrontFacing sees it), not interpolated zero crossings. Each edge is sampled
// every step_px on screen and each sample is tested with an exact ray cast (eye -> point against
// every triangle whose projected bounding box holds the point, binned in 8-px image tiles); the
// ray's continuation tells whether surface lies behind the silhouette (what Toward/Away needs)
// or only background. Output: visible runs as image polylines (pixels, origin top-left, y down)
// with eye distances (world units). This is the reference the GPU methods are scored against.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "lines/line_accuracy.hpp"

namespace penink {

struct ObjectSilhouetteOptions {
    double step_px = 0.25;  // sampling step along each projected edge
};

struct SilhouetteRun {
    ImagePolyline points;        // image pixels
    std::vector<float> depth;    // eye distance per point
    bool surface_behind = true;  // the eye ray continues onto more surface
};

struct ObjectSilhouettes {
    std::vector<SilhouetteRun> runs;
    std::size_t silhouette_edges = 0;  // front/back edges before visibility
};

ObjectSilhouettes object_space_silhouettes(const std::vector<glm::vec3>& pos,
                                           const std::vector<glm::uvec3>& tri, const Camera& cam,
                                           const ObjectSilhouetteOptions& options = {});

// The runs' polylines; with only_surface_behind, those with surface behind them only.
std::vector<ImagePolyline> silhouette_polylines(const ObjectSilhouettes& s, bool only_surface_behind);

}  // namespace penink
