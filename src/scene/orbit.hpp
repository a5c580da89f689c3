// An orbit of a camera around a model (`penink batch SCENE --orbit N`): N cameras, the first the
// given one, each next one turned by 360/N degrees clockwise (seen from above) about the vertical
// axis through the point the first camera looks at (the point of its view ray nearest the centre
// of the model's box [lo, hi]), looking the same way relative to that axis
// (azimuth turned with it, altitude and eye height kept). World frame of conventions.md (z up,
// azimuth clockwise from +y); near/far fitted to the box for every camera. The walk-through of a
// model, the camera path of the walkthrough paper's frame-time table (Potter et al., "NPR-Style
// 3D Line Textures", Table 1).
#pragma once
#include <vector>

#include "core/camera.hpp"

namespace penink {

std::vector<Camera> orbit_cameras(const Camera& start, const glm::dvec3& lo, const glm::dvec3& hi, int frames);

}  // namespace penink
