// Drainage stems: the branch network regrouped into long polylines for drawing. At each junction
// the downstream branch continues the upstream branch of highest Strahler order (ties: larger
// flow at the junction), so a river is one line from its farthest source to the outlet and a
// tributary ends where it joins (as a cartographer draws them). Output: vertex index lists into
// DrainageDb::vertices, junction vertices not repeated, sources first, deterministic.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/drainage_db.hpp"

namespace penink {

std::vector<std::vector<std::uint32_t>> drainage_stems(const DrainageDb& db);

// The basin divides as vertex index lists into DrainageDb::divide_vertices.
std::vector<std::vector<std::uint32_t>> divide_polylines(const DrainageDb& db);

// The pieces of each line (index lists into `vertices`) inside the plan box [lo, hi], local
// metres, with one vertex beyond the box at each cut so lines run to its edge: a view cropped to
// part of a large DEM scores only what it models (prepare_drainage_lines cuts the stored,
// draped lines this way).
std::vector<std::vector<std::uint32_t>> lines_in_box(const std::vector<std::vector<std::uint32_t>>& lines,
                                                     const DvVertices& vertices, glm::vec2 lo, glm::vec2 hi);

}  // namespace penink
