#include "core/floor_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace penink {
namespace {

// floor_index is the clamped floor it replaces for every non-NaN coordinate: integers, values
// just beside them, both signs of zero, below 0, at and beyond the top, and infinities.
TEST(FloorIndex, IsTheClampedFloor) {
    const double inf = std::numeric_limits<double>::infinity();
    for (int hi : {0, 1, 7, 2013}) {
        std::vector<double> xs = {-inf, -1e300, -3.5, -1.0, -0.5, -1e-300, -0.0, 0.0, 1e-300, inf, 1e300};
        for (int k = -2; k <= hi + 3; ++k)
            for (double d : {-0.25, 0.0, 0.25, 0.999999})
                xs.push_back(k + d), xs.push_back(std::nextafter(double(k), -inf)), xs.push_back(std::nextafter(double(k), inf));
        for (double x : xs) EXPECT_EQ(floor_index(x, hi), int(std::clamp(std::floor(x), 0.0, double(hi)))) << x << " " << hi;
    }
}

}  // namespace
}  // namespace penink
