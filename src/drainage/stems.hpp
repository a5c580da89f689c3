// Drainage stems: the branch network regrouped into long polylines for drawing. At each junction
// the downstream branch continues the upstream branch of highest Strahler order (ties: larger
// flow at the junction), so a river is one line from its farthest source to the outlet and a
// tributary ends where it joins (as a cartographer draws them). Output: vertex index lists into
// DrainageDb::vertices, junction vertices not repeated, sources first, deterministic.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/drainage_db.hpp"

namespace penink {

std::vector<std::vector<std::uint32_t>> drainage_stems(const DrainageDb& db);

}  // namespace penink
