// The crease score's parameters (core/crease_params.hpp): the scene's names of eq. 6's
// normalisations and the defaults (the score itself: tests/lines/crease_scores_test.cpp).
#include <gtest/gtest.h>

#include "core/crease_params.hpp"

using namespace penink;

TEST(CreaseScore, NormalisationNames) {
    EXPECT_EQ(score_normalisation_named("thirds"), ScoreNormalisation::thirds);
    EXPECT_EQ(score_normalisation_named("paper"), ScoreNormalisation::paper);
    EXPECT_FALSE(score_normalisation_named("Paper").has_value());
    EXPECT_STREQ(score_normalisation_name(ScoreNormalisation::paper), "paper");
    EXPECT_EQ(crease_defaults().normalisation, ScoreNormalisation::thirds);
}
