// Ties between equally steep neighbours go to the one whose own path gets lower sooner; equal
// paths keep the lowest ESRI code.
#include <tuple>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"

namespace penink {
namespace {

constexpr int W = 7, H = 5;
constexpr std::size_t centre = 2 * W + 3, north = 1 * W + 3, south = 3 * W + 3;

// 20 m everywhere but the given (column, row, metres) nodes; 10 m cells.
DrainageGrid grid_of(std::initializer_list<std::tuple<int, int, float>> nodes) {
    std::vector<float> z(W * H, 20.0f);
    for (const auto& [c, r, v] : nodes) z[std::size_t(r) * W + c] = v;
    return make_regular_grid(W, H, 10.0, z);
}

// (3, 2) at 10 m between N (3, 1) and S (3, 3), both 9 m, which drain to the border nodes
// (3, 0) at `north_end` and (3, 4) at `south_end`.
DrainageGrid tee(float north_end, float south_end) {
    return grid_of({{3, 2, 10.0f}, {3, 1, 9.0f}, {3, 3, 9.0f}, {3, 0, north_end}, {3, 4, south_end}});
}

TEST(D8Ties, TheNeighbourWhosePathDropsSoonerWins) {
    DrainageGrid g = tee(0.0f, 8.0f);  // north: 9 -> 0; south: 9 -> 8
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[centre], 64);  // N, where the lowest code alone would give S (4)
    EXPECT_GE(res.stats.ties, 1u);
}

TEST(D8Ties, EqualPathsKeepTheLowestCode) {
    DrainageGrid g = tee(8.0f, 8.0f);  // both 9 -> 8 -> off the grid
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[centre], 4);
}

TEST(D8Ties, SouthDropsSoonerMirrored) {
    DrainageGrid g = tee(8.0f, 2.0f);
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[centre], 4);
}

TEST(D8Ties, AFlatCellBetweenTwoExitsTakesTheOneThatDropsSooner) {
    // (3, 2) at 10 m has no lower neighbour; its flat neighbours N (3, 1) and S (3, 3), also at
    // 10 m, are exits draining to (3, 0) at 0 m and (3, 4) at 8 m: equal flat gradients.
    DrainageGrid g = grid_of({{3, 2, 10.0f}, {3, 1, 10.0f}, {3, 3, 10.0f}, {3, 0, 0.0f}, {3, 4, 8.0f}});
    const DrainageResult res = compute_drainage(g);
    EXPECT_EQ(res.dir[north], 64);
    EXPECT_EQ(res.dir[south], 4);
    EXPECT_EQ(res.dir[centre], 64);  // the flat resolution alone gives S (4), the lower code
}

}  // namespace
}  // namespace penink
