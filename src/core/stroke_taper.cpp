#include "core/stroke_taper.hpp"

#include <algorithm>

namespace penink {

double taper_factor(double at, double length, double taper, double taper_min) {
    if (!(taper > 0.0)) return 1.0;
    const double zone = std::min(taper, 0.5 * length);
    if (!(zone > 0.0)) return taper_min;
    const double u = std::clamp(std::min(at, length - at) / zone, 0.0, 1.0);
    return taper_min + (1.0 - taper_min) * (1.0 - (1.0 - u) * (1.0 - u));
}

}  // namespace penink
