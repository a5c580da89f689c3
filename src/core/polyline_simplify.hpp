// Polyline simplification in image pixels: Douglas-Peucker (Douglas & Peucker 1973), iterative
// with an explicit stack, distance to the chord segment; optionally also a value carried along
// the polyline (linear in arc length between kept points, as the writers draw a width). Used by
// the lines stage (lines/simplify.hpp) and by the writers (a variable-width stroke's centre line
// and outline, export/stroke_outline.hpp).
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

namespace penink {

// Distance from p to segment [a, b] (pixels).
float point_segment_distance(glm::vec2 p, glm::vec2 a, glm::vec2 b);

// Indices (ascending, first and last always included) of the points of the open polyline
// pts[0..n) that Douglas-Peucker keeps with tolerance tol (pixels). Empty for n == 0.
std::vector<std::size_t> douglas_peucker_indices(const std::vector<glm::vec2>& pts, float tol);

// Same with a value per point (values.size() == pts.size()): a point's error is the larger of
// its distance from the chord and tol x |its value - the chord's| / value_tol, the chord's value
// linear in arc length between the kept points; so every point left out lies within tol of the
// simplified polyline and its value within value_tol of the simplified profile.
std::vector<std::size_t> douglas_peucker_indices(const std::vector<glm::vec2>& pts, float tol,
                                                 const std::vector<float>& values, float value_tol);

// Same for a closed polyline without repeated end point: split at point 0 and the point
// farthest from it, simplify both halves; at least 3 points are kept when n >= 3.
std::vector<std::size_t> douglas_peucker_ring_indices(const std::vector<glm::vec2>& pts, float tol);

}  // namespace penink
