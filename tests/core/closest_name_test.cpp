#include "core/closest_name.hpp"

#include <gtest/gtest.h>

namespace penink {
namespace {

TEST(ClosestName, EditDistanceCountsSwapsAsOneEdit) {
    EXPECT_EQ(edit_distance("fov", "fov"), 0u);
    EXPECT_EQ(edit_distance("fvo", "fov"), 1u);
    EXPECT_EQ(edit_distance("min_scroe", "min_score"), 1u);
    EXPECT_EQ(edit_distance("widht", "width"), 1u);
    EXPECT_EQ(edit_distance("cameras", "camera"), 1u);
    EXPECT_EQ(edit_distance("", "abc"), 3u);
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(ClosestName, SuggestsOnlyANearName) {
    const std::vector<std::string> camera = {"position", "elevation", "azimuth", "altitude", "fov", "width", "height"};
    EXPECT_EQ(closest_name("fvo", camera), "fov");
    EXPECT_EQ(closest_name("altitdue", camera), "altitude");
    EXPECT_EQ(closest_name("widht", camera), "width");
    EXPECT_EQ(closest_name("zoom", camera), "");
    EXPECT_EQ(closest_name("x", camera), "");  // one letter: any name is 1-2 edits away, none meant
    EXPECT_EQ(did_you_mean("fvo", camera), "; did you mean fov?");
    EXPECT_EQ(did_you_mean("speed", camera), "");
}

}  // namespace
}  // namespace penink
