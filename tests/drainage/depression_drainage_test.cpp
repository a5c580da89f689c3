// Inside a filled depression cells drain down the original slopes to its low point, and only the
// low point's path to the spill keeps the filled surface's (flat-resolved) directions.
#include <algorithm>
#include <cstdlib>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"

namespace penink {
namespace {

constexpr int W = 11, H = 7, pc = 5, pr = 3;

// A plane falling east, 0.5 m per 10 m cell, with a stepped bowl around (5, 3): 6 m down at the
// centre, 4 m on the first ring, 2 m on the second. It fills to 1.0 m, the spill being (8, 3).
DrainageGrid bowl() {
    std::vector<float> z(W * H);
    for (int r = 0; r < H; ++r)
        for (int c = 0; c < W; ++c) {
            const int ring = std::max(std::abs(c - pc), std::abs(r - pr));
            const float dip = ring == 0 ? 6.0f : ring == 1 ? 4.0f : ring == 2 ? 2.0f : 0.0f;
            z[std::size_t(r) * W + c] = 0.5f * float(W - 1 - c) - dip;
        }
    return make_regular_grid(W, H, 10.0, z);
}

std::size_t at(int c, int r) { return std::size_t(r) * W + c; }

TEST(DepressionDrainage, RaisedCellsDrainDownTheOriginalSlope) {
    DrainageGrid g = bowl();
    const DrainageResult res = compute_drainage(g);
    EXPECT_GT(res.stats.filled, 0u);
    // (5, 1) at 0.5 m: S (5, 2) at -1.5 m drops 2.0 / 10 = 0.2, SE (6, 2) at -2 m 2.5 / 14.14 = 0.177
    EXPECT_EQ(res.dir[at(5, 1)], 4);  // S, not towards the spill as over the filled flat
    // (3, 3) at 1.0 m: E (4, 3) at -1 m drops 0.2, the steepest
    EXPECT_EQ(res.dir[at(3, 3)], 1);
    // (5, 2) at -1.5 m: S to the centre (-3.5 m) drops 0.2
    EXPECT_EQ(res.dir[at(5, 2)], 4);
}

TEST(DepressionDrainage, TheLowPointLeavesThroughTheSpill) {
    DrainageGrid g = bowl();
    const DrainageResult res = compute_drainage(g);
    const GridShape s{W, H, g.valid.data()};
    EXPECT_GE(res.stats.outflow, 3u);  // the centre, (6, 3), (7, 3) at least
    // from the north rim of the bowl: down to the centre, then east through the spill (8, 3)
    std::size_t c = at(5, 1);
    bool centre = false, spill = false;
    for (int steps = 0; res.dir[c] && steps < 100; ++steps) {
        centre = centre || c == at(pc, pr), spill = spill || c == at(8, 3);
        c = d8_target(s, c, res.dir[c]);
    }
    EXPECT_TRUE(centre);
    EXPECT_TRUE(spill);
    EXPECT_EQ(int(c % W), W - 1);  // out on the east edge
    // the outflow path (6, 3), (7, 3) keeps the flat's direction east; every other cell of the
    // bowl's two rings drains through the centre (and so does the plane west of it, which falls
    // east into the bowl)
    EXPECT_EQ(res.dir[at(6, 3)], 1);
    EXPECT_EQ(res.dir[at(7, 3)], 1);
    for (int r = pr - 2; r <= pr + 2; ++r)
        for (int col = pc - 2; col <= pc + 2; ++col) {
            if (r == pr && col > pc) continue;
            std::size_t x = at(col, r);
            for (int steps = 0; x != at(pc, pr) && res.dir[x] && steps < 100; ++steps)
                x = d8_target(s, x, res.dir[x]);
            EXPECT_EQ(x, at(pc, pr)) << "from (" << col << ", " << r << ")";
        }
    EXPECT_GT(res.net.acc[at(pc, pr)], 25u);
}

}  // namespace
}  // namespace penink
