// Smooths object-space polylines in the horizontal plane: `iterations` passes of Laplacian
// smoothing (each interior point moves halfway to the mean of its two neighbours), end points
// fixed so junctions stay joined. Removes the 45-degree staircase of D8 flow paths before the
// lines are draped back on the surface. Positions in local metres; runs index into `positions`.
#pragma once
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/vertex_run.hpp"

namespace penink {

void smooth_runs_xy(std::vector<glm::vec3>& positions, const std::vector<VertexRun>& runs, int iterations);

// Gaussian smoothing of a polyline along its vertex index (standard deviation `sigma` vertices,
// kernel cut at 3 sigma), ends fixed: beyond each end the polyline continues as its point
// reflection through that end (so the end keeps its place and its tangent). `out` = `in`'s size.
void gaussian_smooth(const std::vector<glm::dvec2>& in, double sigma, std::vector<glm::dvec2>& out);

// A line ending where another passes through (a tributary at its junction with the main stem)
// keeps its end point fixed while smoothing moves the other line's junction vertex: the end
// follows that vertex (in x, y) so the two stay joined. `before` holds the positions before
// smoothing; an end matches an interior vertex of any run at the bit-identical x, y.
void rejoin_line_ends(const std::vector<glm::vec3>& before, const std::vector<VertexRun>& runs,
                      std::vector<glm::vec3>& positions);

}  // namespace penink
