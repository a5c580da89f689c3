// smooth_runs_xy: p_k <- (p_k + (p_{k-1} + p_{k+1}) / 2) / 2 with fixed ends. A sine mode
// sin(pi m k / (n - 1)) of an n-point run vanishes at both ends and is an eigenvector of that
// operator with factor (1 + cos(pi m / (n - 1))) / 2 per iteration; evenly spaced x stays put;
// z is untouched; runs of fewer than 3 points and other runs are unchanged.
#include <cmath>

#include <gtest/gtest.h>

#include "drainage/polyline_smoothing.hpp"

using namespace penink;

namespace {

// n points at x = 10 k, y = amplitude sin(pi m k / (n - 1)) + 5, z = 100 + k.
std::vector<glm::vec3> sine_run(int n, int m, float amplitude) {
    std::vector<glm::vec3> p;
    for (int k = 0; k < n; ++k)
        p.emplace_back(10.0f * k, amplitude * float(std::sin(M_PI * m * k / (n - 1))) + 5.0f, 100.0f + k);
    return p;
}

}  // namespace

TEST(PolylineSmoothing, ZigZagAmplitudeShrinksByModeFactor) {
    // m = 6 of 13 points: 0, A, 0, -A, ... a zig-zag, factor (1 + cos(pi/2)) / 2 = 0.5.
    // m = 4 of 13 points: factor (1 + cos(pi/3)) / 2 = 0.75.
    for (const auto& [m, factor] : {std::pair{6, 0.5}, std::pair{4, 0.75}}) {
        for (int iterations : {1, 2, 3}) {
            const std::vector<glm::vec3> in = sine_run(13, m, 8.0f);
            std::vector<glm::vec3> p = in;
            smooth_runs_xy(p, {{0, 13}}, iterations);
            const double f = std::pow(factor, iterations);
            for (int k = 0; k < 13; ++k) {
                EXPECT_NEAR(p[k].y - 5.0f, (in[k].y - 5.0f) * f, 1e-4) << "m " << m << " it " << iterations << " k " << k;
                EXPECT_NEAR(p[k].x, in[k].x, 1e-4);
                EXPECT_EQ(p[k].z, in[k].z);
            }
        }
    }
}

TEST(PolylineSmoothing, EndPointsFixedAndCornerRounded) {
    std::vector<glm::vec3> p = {{0, 0, 1}, {10, 0, 2}, {20, 0, 3}, {20, 10, 4}, {20, 20, 5}};
    const std::vector<glm::vec3> in = p;
    smooth_runs_xy(p, {{0, 5}}, 1);
    EXPECT_EQ(p.front(), in.front());
    EXPECT_EQ(p.back(), in.back());
    // Corner (20, 0): neighbours' mean (15, 5), halfway -> (17.5, 2.5).
    EXPECT_NEAR(p[2].x, 17.5f, 1e-5);
    EXPECT_NEAR(p[2].y, 2.5f, 1e-5);
    EXPECT_NEAR(p[1].x, 10.0f, 1e-5);  // straight neighbours: (0,0)+(20,0) mean = itself
    EXPECT_NEAR(p[1].y, 0.0f, 1e-5);
    smooth_runs_xy(p, {{0, 5}}, 80);
    EXPECT_EQ(p.front(), in.front());
    EXPECT_EQ(p.back(), in.back());
    for (int k = 1; k < 4; ++k) {  // converges to the evenly spaced chord (0, 0) - (20, 20)
        EXPECT_NEAR(p[k].x, 5.0f * k, 0.01f) << k;
        EXPECT_NEAR(p[k].y, 5.0f * k, 0.01f) << k;
        EXPECT_EQ(p[k].z, in[k].z);
    }
}

TEST(PolylineSmoothing, ShortRunsAndOtherRunsUnchanged) {
    std::vector<glm::vec3> p = {{0, 0, 0}, {5, 9, 0},                   // run of 2
                                {0, 0, 0}, {10, 10, 0}, {20, 0, 0},     // run of 3
                                {7, 7, 7}};                             // outside every run
    const std::vector<glm::vec3> in = p;
    smooth_runs_xy(p, {{0, 2}, {2, 3}}, 4);
    EXPECT_EQ(p[0], in[0]);
    EXPECT_EQ(p[1], in[1]);
    EXPECT_EQ(p[2], in[2]);
    EXPECT_EQ(p[4], in[4]);
    EXPECT_EQ(p[5], in[5]);
    EXPECT_NEAR(p[3].y, 10.0f * std::pow(0.5f, 4), 1e-5);  // (y + 0) / 2 per iteration
    EXPECT_NEAR(p[3].x, 10.0f, 1e-5);
    std::vector<glm::vec3> q = in;
    smooth_runs_xy(q, {{2, 3}}, 0);
    EXPECT_EQ(q, in);
}
