// The automatic vertical exaggeration: a twentieth of the extent as relief, on a nice step,
// within [1, 25].
#include <gtest/gtest.h>

#include "scene/auto_exaggeration.hpp"

using namespace penink;

TEST(AutoExaggeration, FollowsTheReliefAgainstTheExtent) {
    EXPECT_EQ(auto_vertical_exaggeration(101.0, 870.0), 1.0);        // Maunga Whau: already reads
    EXPECT_EQ(auto_vertical_exaggeration(840.0, 32000.0), 2.0);      // Jacksboro: 1.9 -> 2
    EXPECT_EQ(auto_vertical_exaggeration(2000.0, 300000.0), 8.0);    // 7.5 -> 8 (nearer on a log scale than 6)
    EXPECT_EQ(auto_vertical_exaggeration(200.0, 1000.0), 1.0);       // a crater: never below 1
    EXPECT_EQ(auto_vertical_exaggeration(5.0, 30000.0), 25.0);       // a plain: held at 25
    EXPECT_EQ(auto_vertical_exaggeration(0.0, 30000.0), 1.0);        // flat: nothing to exaggerate
    EXPECT_EQ(auto_vertical_exaggeration(1000.0, 264000.0), 12.5);   // 13.2 -> 12.5
    EXPECT_EQ(auto_vertical_exaggeration(1000.0, 0.0), 1.0);
}

TEST(AutoExaggeration, IsMonotoneInTheExtent) {
    double last = 0.0;
    for (double extent = 100.0; extent < 1e6; extent *= 1.1) {
        const double e = auto_vertical_exaggeration(300.0, extent);
        EXPECT_GE(e, last);
        last = e;
    }
    EXPECT_EQ(last, 25.0);
}
