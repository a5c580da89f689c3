// The crease score of eq. 6 (Mower, "Concurrent Drainage Network Rendering"; lines/crease_scores.hpp)
// on known terms: "thirds" and "paper" against the formula written out, the bounds that decide
// which of the paper's tables can draw anything, and the rank normalisation: percentiles with
// ties, hidden vertices left out of the ranking and of the output, the weighted mean of the
// percentiles minus rs_min, and the share passing a threshold for independent uniform terms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lines/crease_scores.hpp"

using namespace penink;

namespace {

CreaseParams weights(double sw, double iw, double fw, ScoreNormalisation n) {
    CreaseParams p;
    p.slope_weight = sw, p.illumination_weight = iw, p.flow_weight = fw, p.normalisation = n;
    p.min_score = 0.0, p.distance_attenuation = 1.0;
    return p;
}

// One visible vertex's terms; with weights()' min_score 0, attenuation 1 and D = 1, rs_min is its
// distance.
CreaseTerms terms(float sc, float ic, float fc, float rs_min) { return {sc, ic, fc, rs_min}; }

float score(const CreaseParams& p, float sc, float ic, float fc, float rs_min) {
    return crease_scores({terms(sc, ic, fc, rs_min)}, p, 1.0f).at(0);
}

// Terms and weights of about 1 in float, a handful of roundings each of at most 6e-8.
constexpr double float_tolerance = 1e-6;

}  // namespace

TEST(CreaseScores, ThirdsDividesTheWeightedSumByThree) {
    const CreaseParams p = weights(2.0, 0.5, 4.0, ScoreNormalisation::thirds);
    // sc .2, ic .4, fc .5: (0.4 + 0.2 + 2.0) / 3 = 0.8666...
    EXPECT_NEAR(score(p, 0.2f, 0.4f, 0.5f, 0.0f), (2.0 * 0.2 + 0.5 * 0.4 + 4.0 * 0.5) / 3.0, float_tolerance);
    EXPECT_NEAR(score(p, 0.2f, 0.4f, 0.5f, 0.12f), 2.6 / 3.0 - 0.12, float_tolerance);
}

TEST(CreaseScores, PaperIsTheWeightedMean) {
    const CreaseParams p = weights(2.0, 0.5, 4.0, ScoreNormalisation::paper);
    EXPECT_NEAR(score(p, 0.2f, 0.4f, 0.5f, 0.0f), 2.6 / 6.5, float_tolerance);
    // Equal terms give that term whatever the weights: a mean.
    EXPECT_NEAR(score(p, 0.3f, 0.3f, 0.3f, 0.0f), 0.3, float_tolerance);
    // Table 5's weights sum to 1: the weighted sum itself.
    const CreaseParams t5 = weights(0.1, 0.3, 0.6, ScoreNormalisation::paper);
    EXPECT_NEAR(score(t5, 0.1f, 0.5f, 1.0f, 0.8f), 0.01 + 0.15 + 0.6 - 0.8, float_tolerance);
    // No weight at all: divided by 1, so only -rs_min remains.
    EXPECT_FLOAT_EQ(score(weights(0, 0, 0, ScoreNormalisation::paper), 1, 1, 1, 0.25f), -0.25f);
}

TEST(CreaseScores, RsMinIsMinScorePlusAttenuationTimesDistanceOverD) {
    CreaseParams p = weights(2.0, 0.5, 4.0, ScoreNormalisation::thirds);
    p.min_score = 0.12, p.distance_attenuation = 0.3;
    // d = 1500 m of D = 2000 m: rs_min = .12 + .3 * .75
    const std::vector<float> rs = crease_scores({terms(0.2f, 0.4f, 0.5f, 1500.0f)}, p, 2000.0f);
    EXPECT_NEAR(rs.at(0), 2.6 / 3.0 - (0.12 + 0.3 * 0.75), float_tolerance);
}

TEST(CreaseScores, HiddenVerticesStayHidden) {
    for (ScoreNormalisation n : {ScoreNormalisation::thirds, ScoreNormalisation::paper, ScoreNormalisation::rank}) {
        const std::vector<float> rs = crease_scores({CreaseTerms{}, terms(0.5f, 0.5f, 0.5f, 0.0f)},
                                                    weights(1, 1, 1, n), 1.0f);
        ASSERT_EQ(rs.size(), 2u);
        EXPECT_EQ(rs[0], dm_hidden) << score_normalisation_name(n);
        EXPECT_NE(rs[1], dm_hidden) << score_normalisation_name(n);
    }
}

TEST(CreaseScores, Table5CanOnlyDrawUnderPaper) {
    // Every term at its largest (1): the highest score a vertex can reach.
    const CreaseParams thirds = weights(0.1, 0.3, 0.6, ScoreNormalisation::thirds);
    const CreaseParams paper = weights(0.1, 0.3, 0.6, ScoreNormalisation::paper);
    EXPECT_LT(score(thirds, 1, 1, 1, 0.8f), 0.0f);  // 1/3 - 0.8
    // Figure 15's .25 under "thirds" asks for a weighted sum of .75: on flat ground, full flow and ic >= .5.
    EXPECT_LT(score(thirds, 0, 0.49f, 1, 0.25f), 0.0f);
    EXPECT_GT(score(paper, 1, 1, 1, 0.8f), 0.0f);
    // Under "paper" .8 asks for strong flow: with no flow the best is .1 + .3 = .4.
    EXPECT_LT(score(paper, 1, 1, 0, 0.8f), 0.0f);
}

TEST(CreaseScores, PercentilesCountHalfTheTiesAndSkipHiddenValues) {
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

TEST(CreaseScores, RankIsTheWeightedMeanOfPercentilesMinusTheThreshold) {
    // slope ranks 1/6, 1/2, 5/6; illumination reversed; flow all equal (1/2); the fourth hidden
    const std::vector<CreaseTerms> t{terms(0.1f, 0.9f, 0.0f, 0.1f), terms(0.2f, 0.5f, 0.0f, 0.2f),
                                     terms(0.3f, 0.2f, 0.0f, 0.3f), CreaseTerms{}};
    const std::vector<float> rs = crease_scores(t, weights(1.0, 3.0, 6.0, ScoreNormalisation::rank), 1.0f);
    const double ranks[3][3] = {{1.0 / 6, 0.5, 5.0 / 6}, {5.0 / 6, 0.5, 1.0 / 6}, {0.5, 0.5, 0.5}};
    for (int i = 0; i < 3; ++i) {
        const double mean = (1.0 * ranks[0][i] + 3.0 * ranks[1][i] + 6.0 * ranks[2][i]) / 10.0;
        EXPECT_NEAR(rs[i], mean - t[i].distance, float_tolerance) << i;
    }
    EXPECT_EQ(rs[3], dm_hidden);
    // no weight: the score is -rs_min
    const std::vector<float> none = crease_scores(t, weights(0.0, 0.0, 0.0, ScoreNormalisation::rank), 1.0f);
    EXPECT_FLOAT_EQ(none[1], -0.2f);
}

// Whatever the terms' own distributions (here flow concentrated near 0 as per-basin flow is),
// ranking makes the share of vertices passing a threshold that of the weighted mean of
// independent uniforms: for Table 5's weights .1/.3/.6 and .8, P(.1U1 + .3U2 + .6U3 >= .8) =
// 7/108 = 6.48 % (integrating over U3 in closed form; 40 000 vertices: standard error 0.12 %, the
// tolerance is 4 of them).
TEST(CreaseScores, RankThresholdKeepsAShareIndependentOfTheTermsDistributions) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const std::size_t n = 40000;
    std::vector<CreaseTerms> t(n);
    for (std::size_t i = 0; i < n; ++i) {
        t[i].slope = 0.5f * u(rng);
        t[i].illumination = u(rng);
        t[i].flow = std::pow(u(rng), 8.0f);  // most flow near 0
        t[i].distance = 0.0f;
    }
    CreaseParams p = weights(0.1, 0.3, 0.6, ScoreNormalisation::rank);
    p.min_score = 0.8;
    std::size_t passing = 0;
    for (float s : crease_scores(t, p, 1.0f)) passing += s >= 0.0f;
    EXPECT_NEAR(double(passing) / n, 7.0 / 108.0, 0.005);
}

// A term with weight 0 is not ranked: the scores are those of its percentiles' mean without it,
// whatever its values.
TEST(CreaseScores, RankIgnoresUnweightedTerms) {
    std::vector<CreaseTerms> t{terms(0.1f, 0.9f, 0.3f, 0.1f), terms(0.2f, 0.5f, 0.1f, 0.2f),
                               terms(0.3f, 0.2f, 0.2f, 0.3f), CreaseTerms{}};
    const CreaseParams p = weights(1.0, 2.0, 0.0, ScoreNormalisation::rank);
    const std::vector<float> a = crease_scores(t, p, 1.0f);
    for (CreaseTerms& v : t) v.flow = 0.7f - v.flow;
    const std::vector<float> b = crease_scores(t, p, 1.0f);
    ASSERT_EQ(a.size(), 4u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
    EXPECT_NEAR(a[0], (1.0 / 6 + 2.0 * 5.0 / 6) / 3.0 - 0.1, float_tolerance);
}
