#include "scene/auto_exaggeration.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace penink {

double auto_vertical_exaggeration(double relief_m, double extent_m) {
    if (!(relief_m > 0.0) || !(extent_m > 0.0) || !std::isfinite(relief_m) || !std::isfinite(extent_m)) return 1.0;
    const double raw = auto_exaggeration_relief_share * extent_m / relief_m;
    if (!(raw > 1.0)) return 1.0;
    static constexpr double steps[] = {1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0};
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    double best = 1.0, best_gap = 1e300;
    for (double s : steps) {
        const double gap = std::abs(std::log(s * decade / raw));
        if (gap < best_gap) best = s * decade, best_gap = gap;
    }
    return std::clamp(best, 1.0, max_auto_exaggeration);
}

std::string describe_auto_exaggeration(double relief_m, double extent_m, double exaggeration) {
    std::ostringstream s;
    s.precision(4);
    s << "relief " << relief_m << " m over " << extent_m << " m: vertical exaggeration " << exaggeration << " (auto)";
    return s.str();
}

}  // namespace penink
