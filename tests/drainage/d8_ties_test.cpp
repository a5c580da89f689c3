// Ties between equally steep neighbours go to the one whose own path gets lower sooner; equal
// paths keep the lowest ESRI code.
#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"

namespace penink {
namespace {

constexpr int W = 7, H = 5;

// (3, 2) at 10 m between N (3, 1) and S (3, 3), both 9 m; everything else 20 m but (3, 0) at
// `north_end` and (3, 4) at 8 m on the border.
DrainageGrid tee(float north_end) {
    std::vector<float> z(W * H, 20.0f);
    auto set = [&](int c, int r, float v) { z[std::size_t(r) * W + c] = v; };
    set(3, 2, 10.0f), set(3, 1, 9.0f), set(3, 3, 9.0f), set(3, 0, north_end), set(3, 4, 8.0f);
    return make_regular_grid(W, H, 10.0, z);
}

TEST(D8Ties, TheNeighbourWhosePathDropsSoonerWins) {
    DrainageGrid g = tee(0.0f);  // north: 9 -> 0; south: 9 -> 8
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[2 * W + 3], 64);  // N, where the lowest code alone would give S (4)
    EXPECT_GE(res.stats.ties, 1u);
}

TEST(D8Ties, EqualPathsKeepTheLowestCode) {
    DrainageGrid g = tee(8.0f);  // both 9 -> 8 -> off the grid
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[2 * W + 3], 4);
}

TEST(D8Ties, SouthDropsSoonerMirrored) {
    std::vector<float> z(W * H, 20.0f);
    auto set = [&](int c, int r, float v) { z[std::size_t(r) * W + c] = v; };
    set(3, 2, 10.0f), set(3, 1, 9.0f), set(3, 3, 9.0f), set(3, 0, 8.0f), set(3, 4, 2.0f);
    DrainageGrid g = make_regular_grid(W, H, 10.0, z);
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[2 * W + 3], 4);
}

TEST(D8Ties, AFlatCellBetweenTwoExitsTakesTheOneThatDropsSooner) {
    // (3, 2) at 10 m has no lower neighbour; its flat neighbours N (3, 1) and S (3, 3), also at
    // 10 m, are exits draining to (3, 0) at 0 m and (3, 4) at 8 m: equal flat gradients.
    std::vector<float> z(W * H, 20.0f);
    auto set = [&](int c, int r, float v) { z[std::size_t(r) * W + c] = v; };
    set(3, 2, 10.0f), set(3, 1, 10.0f), set(3, 3, 10.0f), set(3, 0, 0.0f), set(3, 4, 8.0f);
    DrainageGrid g = make_regular_grid(W, H, 10.0, z);
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[1 * W + 3], 64);
    EXPECT_EQ(res.dir[3 * W + 3], 4);
    EXPECT_EQ(res.dir[2 * W + 3], 64);  // the flat resolution alone gives S (4), the lower code
}

}  // namespace
}  // namespace penink
