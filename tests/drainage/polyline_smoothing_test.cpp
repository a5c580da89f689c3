// Gaussian smoothing of polylines (drainage/polyline_smoothing.hpp): a kernel made once and used on
// many polylines gives gaussian_smooth's floats on each, the ends stay fixed and a straight,
// evenly spaced line is left where it is.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drainage/polyline_smoothing.hpp"

namespace penink {
namespace {

std::vector<glm::dvec2> zigzag(int n, double phase) {
    std::vector<glm::dvec2> p;
    for (int k = 0; k < n; ++k) p.push_back({k + 0.25 * std::sin(phase + k), (k % 2) * 0.7 + 0.1 * k * k});
    return p;
}

TEST(PolylineSmoothing, OneKernelForManyLinesGivesGaussianSmoothsFloats) {
    for (const double sigma : {0.0, 1.0, 2.0, 3.5}) {
        const GaussianKernel kernel(sigma);
        std::vector<glm::dvec2> reused, fresh;
        for (int n : {1, 2, 3, 5, 9, 40, 4}) {  // shorter and longer than the kernel, in turn
            const std::vector<glm::dvec2> in = zigzag(n, n * 0.3);
            kernel.smooth(in, reused);
            gaussian_smooth(in, sigma, fresh);
            ASSERT_EQ(reused.size(), in.size());
            for (std::size_t k = 0; k < in.size(); ++k) {  // bit for bit
                EXPECT_EQ(reused[k].x, fresh[k].x) << sigma << " " << n << " " << k;
                EXPECT_EQ(reused[k].y, fresh[k].y) << sigma << " " << n << " " << k;
            }
            EXPECT_EQ(reused.front(), in.front());
            EXPECT_EQ(reused.back(), in.back());
        }
    }
}

TEST(PolylineSmoothing, StraightEvenLineStaysPut) {
    std::vector<glm::dvec2> line, out;
    for (int k = 0; k < 30; ++k) line.push_back({2.0 * k, -1.0 * k});
    GaussianKernel(2.0).smooth(line, out);
    // the reflection through the ends continues the line: every vertex keeps its place (to
    // rounding of sums of about 13 terms of size 60)
    for (std::size_t k = 0; k < line.size(); ++k) {
        EXPECT_NEAR(out[k].x, line[k].x, 1e-12);
        EXPECT_NEAR(out[k].y, line[k].y, 1e-12);
    }
}

}  // namespace
}  // namespace penink
