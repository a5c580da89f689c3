// Smooths plan polylines (the 45-degree staircase of D8 flow paths and divides) before the lines
// are draped back on the surface (draped_lines.hpp).
#pragma once
#include <vector>

#include <glm/vec2.hpp>

namespace penink {

// Gaussian smoothing of a polyline along its vertex index (standard deviation `sigma` vertices,
// kernel cut at 3 sigma), ends fixed: beyond each end the polyline continues as its point
// reflection through that end (so the end keeps its place and its tangent). `out` = `in`'s size.
void gaussian_smooth(const std::vector<glm::dvec2>& in, double sigma, std::vector<glm::dvec2>& out);

}  // namespace penink
