#include "lines/distance_thinning.hpp"

#include <algorithm>
#include <cmath>

#include "lines/random_bits.hpp"

namespace penink {

double keep_probability(float depth, float near, float far, float keep_far) {
    const double low = std::clamp(double(keep_far), 0.0, 1.0);
    if (!std::isfinite(depth)) return low;
    if (depth <= near) return 1.0;
    if (depth >= far || far <= near) return low;
    double t = (double(depth) - near) / (double(far) - near);
    return 1.0 + (low - 1.0) * t;
}

bool keep_stroke(float depth, float near, float far, float keep_far, std::uint64_t seed, std::uint64_t id) {
    constexpr std::uint64_t kDraw = 0x7468696eull;  // "thin": draw number reserved for thinning
    return random_unit(seed, id, kDraw) < keep_probability(depth, near, far, keep_far);
}

}  // namespace penink
