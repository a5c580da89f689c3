// A run of consecutive vertices in a shared vertex array: a polyline stored as [first, first +
// count) (drainage lines, scored crease and ridge polylines).
#pragma once
#include <cstdint>

namespace penink {

struct VertexRun {
    std::uint32_t first = 0, count = 0;  // vertices [first, first + count)
};

}  // namespace penink
