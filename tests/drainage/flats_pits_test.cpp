// Flats and closed depressions must not break the network: a valley with a flat floor and a
// closed depression still drains from its head to the outlet on the east edge.
#include <cmath>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/priority_flood.hpp"

namespace penink {
namespace {

constexpr int W = 40, H = 21, mid = 10;

// Valley along row 10 falling east (0.1 m per cell), 2 m per row up the sides, floor rows 9..11;
// flat floor for columns 10..25, a 3 m deep closed depression at columns 28..31.
DrainageGrid valley() {
    std::vector<float> z(W * H);
    for (int r = 0; r < H; ++r)
        for (int c = 0; c < W; ++c) {
            const float side = 2.0f * float(std::max(std::abs(r - mid) - 1, 0));
            float along = 0.1f * float(W - c);
            if (c >= 10 && c <= 25) along = 0.1f * float(W - 25);
            if (c >= 28 && c <= 31 && std::abs(r - mid) <= 1) along -= 3.0f;
            z[std::size_t(r) * W + c] = side + along;
        }
    return make_regular_grid(W, H, 10.0, z);
}

TEST(FlatsAndPits, ValleyHeadReachesTheEastOutlet) {
    DrainageGrid g = valley();
    const std::vector<float> original = g.z;
    DrainageResult res = compute_drainage(g);
    EXPECT_EQ(g.z, original);  // the fill is undone
    EXPECT_EQ(res.stats.unresolved_flats, 0u);
    EXPECT_EQ(res.stats.filled, 12u);  // the 4x3 depression
    const GridShape s{W, H, g.valid.data()};
    std::size_t c = std::size_t(mid) * W + 1;
    int steps = 0;
    while (res.dir[c] && steps < 1000) {
        const int row = int(c / W);
        EXPECT_LE(std::abs(row - mid), 1) << "left the valley floor at column " << c % W;
        c = d8_target(s, c, res.dir[c]), ++steps;
    }
    EXPECT_EQ(int(c % W), W - 1);  // ends on the east edge
    EXPECT_LE(std::abs(int(c / W) - mid), 1);
    EXPECT_GE(res.net.acc[c], 39u * 3u);  // the whole valley floor drains through it
    EXPECT_EQ(res.net.basin[c], res.net.basin[std::size_t(mid) * W + 1]);
}

TEST(FlatsAndPits, FlatFloorDrainsAlongItsMiddle) {
    DrainageGrid g = valley();
    DrainageResult res = compute_drainage(g);
    const GridShape s{W, H, g.valid.data()};
    // Barnes et al.: away from higher terrain keeps the channel in the middle row of the floor.
    for (int col = 12; col <= 23; ++col)
        EXPECT_EQ(res.dir[std::size_t(mid) * W + col], 1) << "column " << col;
    (void)s;
}

TEST(FlatsAndPits, PriorityFloodRaisesToTheSpillLevel) {
    // 5x5 bowl: rim 5, inner ring 3, centre 1, one rim cell at 2 -> filled to 3 (inner ring), the
    // centre raised to 3.
    std::vector<float> z(25, 5.0f);
    for (int r = 1; r <= 3; ++r)
        for (int c = 1; c <= 3; ++c) z[r * 5 + c] = 3.0f;
    z[12] = 1.0f;
    z[2] = 2.0f;
    DrainageGrid g = make_regular_grid(5, 5, 1.0, z);
    std::vector<std::uint8_t> flags;
    CellWords orig;
    const FillStats st = priority_flood_fill(g.z, {5, 5, g.valid.data()}, flags, orig);
    EXPECT_EQ(st.raised, 1u);
    for (int i = 0; i < 25; ++i) {
        const bool border = i < 5 || i >= 20 || i % 5 == 0 || i % 5 == 4;
        EXPECT_EQ(flags[i], i == 12 ? 3 : border ? 1 | fill_boundary : 1) << i;
    }
    EXPECT_FLOAT_EQ(std::bit_cast<float>(orig[12]), 1.0f);
    EXPECT_FLOAT_EQ(g.z[12], 3.0f);
    EXPECT_FLOAT_EQ(g.z[2], 2.0f);
    swap_raised(g.z, flags, orig);
    EXPECT_EQ(g.z, z);
}

TEST(FlatsAndPits, EveryCellOfATerracedGridReachesAnOutlet) {
    // Staircase terraces with flats and pits everywhere; acc at outlets sums to the cell count.
    const int n = 64;
    std::vector<float> z(n * n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            z[r * n + c] = float(((r * 7 + c * 3) % 11) / 4) + float((c / 8 + r / 8) % 3);
    DrainageGrid g = make_regular_grid(n, n, 1.0, z);
    DrainageResult res = compute_drainage(g);
    std::uint64_t total = 0;
    for (std::uint32_t o : res.net.outlet) {
        total += res.net.acc[o];
        EXPECT_TRUE(is_boundary_cell({n, n, g.valid.data()}, int(o % n), int(o / n)));
    }
    EXPECT_EQ(total, std::uint64_t(n) * n);
    EXPECT_EQ(res.stats.unresolved_flats, 0u);
}

}  // namespace
}  // namespace penink
