// Hidden-line removal for object-space lines on meshes (PELs, silhouettes, feature edges,
// textures): a depth image (eye distance per pixel in world units, +inf where empty, row 0 at
// the top, as the GPU pass writes it), a CPU z-buffer rasteriser of a TriangleMesh that makes
// one (reference for the GPU pass and for tests), and the split of 3D polylines into visible runs
// by sampling about every 0.5 px against the depth image. Pixels and camera: core/camera.hpp.
#pragma once
#include <limits>
#include <vector>

#include "core/camera.hpp"
#include "core/drawing.hpp"
#include "core/triangle_mesh.hpp"
#include "lines/photic_extremum_lines.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

// DepthImage (core/pixel_mask.hpp): width * height eye distances, row-major, row 0 top,
// +inf where nothing was drawn.

// Eye distance of the nearest triangle at each pixel centre (perspective-correct), both
// facings; triangles with a vertex behind the near plane are skipped.
DepthImage rasterize_depth(const TriangleMesh& mesh, const Camera& cam);

struct VisibilityOptions {
    float step_px = 0.5f;         // sampling step along the projected line
    float rel_tolerance = 0.03f;  // visible when d <= depth * (1 + rel) + abs (0.03 keeps the
                                  // interpolated-normal silhouettes of coarse meshes unbroken)
    float abs_tolerance = 0.0f;   // world units
};

// True when the world point is in front of the image content near its pixel (max depth of the
// 3x3 neighbourhood, so lines on a silhouette survive). Outside the camera image: false; an
// empty DepthImage (0 x 0) means no occlusion test (everything inside the image is visible).
// (With the camera's PixelProjector made once, for many points.)
bool point_visible(const DepthImage& img, const Camera& cam, const PixelProjector& project, const glm::vec3& p,
                   const VisibilityOptions& o);
bool point_visible(const DepthImage& img, const Camera& cam, const glm::vec3& p,
                   const VisibilityOptions& options = {});
// The same test for a point already projected: image pixel px, eye distance depth.
bool pixel_visible(const DepthImage& img, const Camera& cam, glm::dvec2 px, double depth, const VisibilityOptions& o);

// Visible runs of each polyline as image-space strokes (pixels + eye distance per point),
// keeping the polyline's vertices and the run ends; kind and strength are copied.
std::vector<Stroke> visible_strokes(const std::vector<ObjectPolyline>& lines, const DepthImage& img,
                                    const Camera& cam, const VisibilityOptions& options = {});

}  // namespace penink
