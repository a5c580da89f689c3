// The grid index of a coordinate: int(std::clamp(std::floor(x), 0.0, double(hi))) for x not NaN,
// without floor (a library-free floor on x86-64's baseline SSE2 takes a dozen instructions):
// x below 0 gives 0, x at hi or above gives hi, between them floor(x) is x truncated. Used in
// the per-vertex loops of the drainage lines (a fall-line trace reads it a few times a vertex).
#pragma once

namespace penink {

inline int floor_index(double x, int hi) {
    if (!(x >= 0.0)) return 0;
    if (x >= double(hi)) return hi;
    return int(x);
}

}  // namespace penink
