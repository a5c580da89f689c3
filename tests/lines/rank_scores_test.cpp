// Rank normalisation of the crease score (lines/rank_scores.hpp) on known terms: percentiles with
// ties, hidden vertices left out of the ranking and of the output, the weighted mean of the
// percentiles minus rs_min, and the share passing a threshold for independent uniform terms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lines/rank_scores.hpp"

using namespace penink;

namespace {
constexpr float dm_hidden = -1.0e30f;  // render/dm.hpp's dm_hidden
}

TEST(RankScores, PercentilesCountHalfTheTiesAndSkipHiddenValues) {
    const float h = dm_hidden;
    const std::vector<float> p = visible_percentiles({0.3f, h, 0.1f, 0.3f, 0.9f}, h);
    // visible: .1 < .3 = .3 < .9, four values: .1 -> .5/4, .3 -> (1 + 1)/4, .9 -> 3.5/4
    EXPECT_FLOAT_EQ(p[2], 0.125f);
    EXPECT_FLOAT_EQ(p[0], 0.5f);
    EXPECT_FLOAT_EQ(p[3], 0.5f);
    EXPECT_FLOAT_EQ(p[4], 0.875f);
    EXPECT_EQ(p[1], h);
    // a term equal everywhere ranks 1/2 everywhere
    for (float v : visible_percentiles({0.0f, 0.0f, 0.0f}, h)) EXPECT_FLOAT_EQ(v, 0.5f);
}

TEST(RankScores, WeightedMeanOfPercentilesMinusTheThreshold) {
    const float h = dm_hidden;
    // slope ranks 1/6, 1/2, 5/6; illumination reversed; flow all equal (1/2)
    const std::array<std::vector<float>, 3> terms{std::vector<float>{0.1f, 0.2f, 0.3f, h},
                                                  std::vector<float>{0.9f, 0.5f, 0.2f, h},
                                                  std::vector<float>{0.0f, 0.0f, 0.0f, h}};
    const std::vector<float> minus_rs_min{-0.1f, -0.2f, -0.3f, h};
    const std::vector<float> rs = rank_scores(terms, minus_rs_min, {1.0, 3.0, 6.0}, h);
    const double ranks[3][3] = {{1.0 / 6, 0.5, 5.0 / 6}, {5.0 / 6, 0.5, 1.0 / 6}, {0.5, 0.5, 0.5}};
    for (int i = 0; i < 3; ++i) {
        const double mean = (1.0 * ranks[0][i] + 3.0 * ranks[1][i] + 6.0 * ranks[2][i]) / 10.0;
        EXPECT_NEAR(rs[i], mean + minus_rs_min[i], 1e-6) << i;
    }
    EXPECT_EQ(rs[3], h);
    // no weight: the score is -rs_min
    const std::vector<float> none = rank_scores(terms, minus_rs_min, {0.0, 0.0, 0.0}, h);
    EXPECT_FLOAT_EQ(none[1], -0.2f);
    EXPECT_THROW(rank_scores(terms, {0.0f}, {1.0, 1.0, 1.0}, h), std::invalid_argument);
}

// Whatever the terms' own distributions (here flow concentrated near 0 as per-basin flow is),
// ranking makes the share of vertices passing a threshold that of the weighted mean of
// independent uniforms: for Table 5's weights .1/.3/.6 and .8, P(.1U1 + .3U2 + .6U3 >= .8) =
// 7/108 = 6.48 % (integrating over U3 in closed form; 40 000 vertices: standard error 0.12 %, the
// tolerance is 4 of them).
TEST(RankScores, ThresholdKeepsAShareIndependentOfTheTermsDistributions) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const std::size_t n = 40000;
    std::array<std::vector<float>, 3> terms;
    for (auto& t : terms) t.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        terms[0][i] = 0.5f * u(rng);
        terms[1][i] = u(rng);
        terms[2][i] = std::pow(u(rng), 8.0f);  // most flow near 0
    }
    const std::vector<float> rs = rank_scores(terms, std::vector<float>(n, -0.8f), {0.1, 0.3, 0.6}, dm_hidden);
    std::size_t passing = 0;
    for (float s : rs) passing += s >= 0.0f;
    EXPECT_NEAR(double(passing) / n, 7.0 / 108.0, 0.005);
}

// A term with weight 0 is neither ranked nor read: it may be left empty (the scene runs no DM pass
// for it), and the scores equal those with it present.
TEST(RankScores, UnweightedTermsAreNotRead) {
    const float h = dm_hidden;
    const std::array<std::vector<float>, 3> full{std::vector<float>{0.1f, 0.2f, 0.3f, h},
                                                 std::vector<float>{0.9f, 0.5f, 0.2f, h},
                                                 std::vector<float>{0.3f, 0.1f, 0.2f, h}};
    const std::array<std::vector<float>, 3> no_flow{full[0], full[1], std::vector<float>{}};
    const std::vector<float> minus_rs_min{-0.1f, -0.2f, -0.3f, h};
    const std::vector<float> a = rank_scores(full, minus_rs_min, {1.0, 2.0, 0.0}, h);
    const std::vector<float> b = rank_scores(no_flow, minus_rs_min, {1.0, 2.0, 0.0}, h);
    ASSERT_EQ(a.size(), 4u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
    EXPECT_NEAR(a[0], (1.0 / 6 + 2.0 * 5.0 / 6) / 3.0 - 0.1, 1e-6);
    EXPECT_THROW(rank_scores(no_flow, minus_rs_min, {1.0, 2.0, 1.0}, h), std::invalid_argument);
}
