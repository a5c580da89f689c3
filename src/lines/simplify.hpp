// Stroke and ring simplification in image pixels: Douglas-Peucker (core/polyline_simplify.hpp);
// kept points keep their depth values.
// Closed strokes (first point repeated at the end) and rings (implicitly closed) stay closed.
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"
#include "core/polyline_simplify.hpp"

namespace penink {

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

// point_segment_distance and douglas_peucker_indices: core/polyline_simplify.hpp.
// is_closed(stroke): core/drawing.hpp.

}  // namespace penink
