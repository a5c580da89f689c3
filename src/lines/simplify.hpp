// Polyline simplification in image pixels: Douglas-Peucker (Douglas & Peucker 1973), iterative
// with an explicit stack, distance to the chord segment; kept points keep their depth values.
// Closed strokes (first point repeated at the end) and rings (implicitly closed) stay closed.
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"

namespace penink {

// Indices (ascending, first and last always included) of the points of the open polyline
// pts[0..n) that Douglas-Peucker keeps with tolerance tol (pixels). Empty for n == 0.
std::vector<std::size_t> douglas_peucker_indices(const std::vector<glm::vec2>& pts, float tol);

// Same for a closed polyline without repeated end point: split at point 0 and the point
// farthest from it, simplify both halves; at least 3 points are kept when n >= 3.
std::vector<std::size_t> douglas_peucker_ring_indices(const std::vector<glm::vec2>& pts, float tol);

// Simplified copy of a stroke (depth, strength and kind kept); tol <= 0 only removes
// duplicate consecutive points. A closed stroke stays closed (first point repeated at the end).
// An open stroke with a weight per point also keeps the points whose weight lies more than
// kWeightTolerance off the chord's (the width the style draws follows the weight: the hachures'
// widths carry their tone).
inline constexpr float kWeightTolerance = 0.05f;
Stroke simplify_stroke(const Stroke& s, float tol);
std::vector<Stroke> simplify_strokes(const std::vector<Stroke>& strokes, float tol);

// Simplified ring (no repeated end point); rings with fewer than 3 points are returned as is.
Ring simplify_ring(const Ring& ring, float tol);

// Drops points of a ring that lie exactly (within eps px) on the line through their neighbours.
Ring remove_collinear(const Ring& ring, float eps = 1e-6f);

// Distance from p to segment [a, b] (pixels).
float point_segment_distance(glm::vec2 p, glm::vec2 a, glm::vec2 b);

// is_closed(stroke): core/drawing.hpp.

}  // namespace penink
