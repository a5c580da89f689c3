// The outline of a variable-width stroke, for the writers that fill it (SVG, PS/EPS, PDF): a
// polyline (image pixels) with one width per point becomes one closed polygon: the centre line
// offset by half the width on its left, forward, a round cap, the right side backward and a round
// cap (zero-width ends close to a point). Joins are round on the outer side and mitred (at most
// twice the half-width) on the inner side; where a mitre stays within 0.05 px of the round join
// (and under 10 degrees of turn always) both sides are mitred. Arcs are chords within 0.05 px.
// Then the polygon is simplified, Douglas-Peucker at 0.05 px (core/polyline_simplify.hpp): it
// stays within 0.1 px of the round outline, the points along straight or gently curving sides
// (one per centre-line point) left out.
// Fill with the nonzero rule: a stroke crossing itself stays solid.
#pragma once
#include <vector>

#include <glm/vec2.hpp>

namespace penink {

// points and widths of the same size (>= 1; consecutive repeated points are skipped); the
// polygon's first point is not repeated at its end.
std::vector<glm::vec2> stroke_outline(const std::vector<glm::vec2>& points, const std::vector<double>& widths);

}  // namespace penink
