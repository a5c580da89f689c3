// Exact silhouettes of the analytic terrains of support/synthetic_terrain.hpp for a camera
// (core/camera.hpp): the contour generator n(p) . (eye - p) = 0 of the smooth surface in closed
// form where it exists (hemisphere: the tangent circle of the sphere; ridge: two lines
// x = x* solving f'(x)(x - ex) + ez - f(x) = 0, the same for every y; cliff: its top edge y = 0,
// z = height when the step faces the eye on one side only, plus the hidden foot) or by
// bisection to 1e-9 m along 7200 rays from the axis (Gaussian hill); a plain has none. Visible
// parts only (ray marched against the exact height function, 1 m steps, stopping 0.5 % short of
// the point where rays graze); optionally only where the eye ray continues onto terrain inside
// the extent (what Toward/Away can see). Output: image polylines in pixels (origin top-left,
// y down), the same frame as lines/line_accuracy.hpp's ImagePolyline.
#pragma once
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "support/synthetic_terrain.hpp"

namespace penink {

// Contour generator as world-space curves (ordered points, a few metres apart or closer).
std::vector<std::vector<glm::dvec3>> analytic_contour_generator(const AnalyticTerrain& shape, const glm::dvec3& eye);

// Visible, projected reference silhouettes; only_surface_behind keeps the parts with terrain
// behind them. Points farther than 5 px apart on screen start a new polyline.
std::vector<std::vector<glm::vec2>> analytic_silhouettes(const AnalyticTerrain& shape, const Camera& cam,
                                                         bool only_surface_behind = true);

}  // namespace penink
