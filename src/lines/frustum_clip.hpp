// Clips 3D polylines (world frame) to a camera's view frustum before they are sampled in image
// space: segments are cut with Liang-Barsky in homogeneous clip coordinates against the six
// planes (grown by `margin` of the half-width on the four sides), so a line passing near or
// behind the eye never becomes a huge projected segment. Output: the inside pieces.
#pragma once
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace penink {

std::vector<std::vector<glm::vec3>> clip_polylines_to_frustum(const std::vector<std::vector<glm::vec3>>& lines,
                                                             const glm::dmat4& view_projection,
                                                             double margin = 0.02);

}  // namespace penink
