// The crease score of eq. 6 (Mower, "Concurrent Drainage Network Rendering") under both
// normalisations, against the formula written out with known terms (core/crease_params.hpp), and
// the bounds that decide which of the paper's tables can draw anything.
#include <gtest/gtest.h>

#include "core/crease_params.hpp"

using namespace penink;

namespace {

CreaseParams weights(double sw, double iw, double fw, ScoreNormalisation n) {
    CreaseParams p;
    p.slope_weight = sw, p.illumination_weight = iw, p.flow_weight = fw, p.normalisation = n;
    return p;
}

}  // namespace

TEST(CreaseScore, ThirdsDividesTheWeightedSumByThree) {
    const CreaseParams p = weights(2.0, 0.5, 4.0, ScoreNormalisation::thirds);
    // sc .2, ic .4, fc .5: (0.4 + 0.2 + 2.0) / 3 = 0.8666...
    EXPECT_DOUBLE_EQ(crease_score(p, 0.2, 0.4, 0.5, 0.0), (2.0 * 0.2 + 0.5 * 0.4 + 4.0 * 0.5) / 3.0);
    EXPECT_DOUBLE_EQ(crease_score(p, 0.2, 0.4, 0.5, 0.12), 2.6 / 3.0 - 0.12);
    EXPECT_DOUBLE_EQ(crease_score_divisor(p), 3.0);
}

TEST(CreaseScore, PaperIsTheWeightedMean) {
    const CreaseParams p = weights(2.0, 0.5, 4.0, ScoreNormalisation::paper);
    EXPECT_DOUBLE_EQ(crease_score(p, 0.2, 0.4, 0.5, 0.0), 2.6 / 6.5);
    // Equal terms give that term whatever the weights: a mean.
    EXPECT_DOUBLE_EQ(crease_score(p, 0.3, 0.3, 0.3, 0.0), 0.3);
    // Table 5's weights sum to 1: the weighted sum itself.
    const CreaseParams t5 = weights(0.1, 0.3, 0.6, ScoreNormalisation::paper);
    EXPECT_DOUBLE_EQ(crease_score(t5, 0.1, 0.5, 1.0, 0.8), 0.01 + 0.15 + 0.6 - 0.8);
    // No weight at all: divided by 1, so only -rs_min remains.
    EXPECT_DOUBLE_EQ(crease_score(weights(0, 0, 0, ScoreNormalisation::paper), 1, 1, 1, 0.25), -0.25);
}

TEST(CreaseScore, Table5CanOnlyDrawUnderPaper) {
    // Every term at its largest (1): the highest score a vertex can reach.
    const CreaseParams thirds = weights(0.1, 0.3, 0.6, ScoreNormalisation::thirds);
    const CreaseParams paper = weights(0.1, 0.3, 0.6, ScoreNormalisation::paper);
    EXPECT_LT(crease_score(thirds, 1, 1, 1, 0.8), 0.0);   // 1/3 - 0.8
    // Figure 15's .25 under "thirds" asks for a weighted sum of .75: on flat ground, full flow and ic >= .5.
    EXPECT_LT(crease_score(thirds, 0, 0.49, 1, 0.25), 0.0);
    EXPECT_GT(crease_score(paper, 1, 1, 1, 0.8), 0.0);
    // Under "paper" .8 asks for strong flow: with no flow the best is .1 + .3 = .4.
    EXPECT_LT(crease_score(paper, 1, 1, 0, 0.8), 0.0);
}

TEST(CreaseScore, NormalisationNames) {
    EXPECT_EQ(score_normalisation_named("thirds"), ScoreNormalisation::thirds);
    EXPECT_EQ(score_normalisation_named("paper"), ScoreNormalisation::paper);
    EXPECT_FALSE(score_normalisation_named("Paper").has_value());
    EXPECT_STREQ(score_normalisation_name(ScoreNormalisation::paper), "paper");
    EXPECT_EQ(crease_defaults().normalisation, ScoreNormalisation::thirds);
}
