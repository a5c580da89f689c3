// The pyramid's errors settled in strips (surface/terrain_lod.hpp, lod_errors): bit for bit the
// errors of the whole padded square settled at once (one strip as tall as the square, every
// level on it: the bottom-up build as terrain_lod.hpp states it), on random grids of odd and
// power-of-two sizes with nodata holes, for strips of one row up to taller than the square and
// fine levels from 2 to the whole square; every row handed over once.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "surface/terrain_lod.hpp"

using namespace penink;

namespace {

struct Grid {
    int cols, rows;
    std::vector<float> z;
    std::vector<std::uint8_t> valid;
    LodHeights heights() const { return {cols, rows, z.data(), valid.data()}; }
};

// Rough random heights (a random walk along rows plus noise) with about `holes` of the nodes
// nodata, in blobs and single nodes; nodata nodes hold garbage heights (never to be read).
Grid random_grid(int cols, int rows, double holes, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Grid g{cols, rows, std::vector<float>(std::size_t(cols) * rows), std::vector<std::uint8_t>(std::size_t(cols) * rows, 1)};
    for (int r = 0; r < rows; ++r) {
        float walk = 100.0f * u(rng);
        for (int c = 0; c < cols; ++c) {
            walk += 3.0f * u(rng);
            g.z[std::size_t(r) * cols + c] = walk + 0.25f * float(r) + u(rng);
        }
    }
    std::bernoulli_distribution hole(holes);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            if (hole(rng)) {
                const int blob = int(rng() % 4);
                for (int dr = 0; dr <= blob && r + dr < rows; ++dr)
                    for (int dc = 0; dc <= blob && c + dc < cols; ++dc) {
                        g.valid[std::size_t(r + dr) * cols + c + dc] = 0;
                        g.z[std::size_t(r + dr) * cols + c + dc] = 1e30f;
                    }
            }
    return g;
}

// The errors, padded row-major, from lod_errors; each row handed over exactly once.
std::vector<float> errors(const Grid& g, LodStrips strips) {
    const int side = (1 << lod_padded_levels(g.cols, g.rows)) + 1;
    std::vector<float> e(std::size_t(side) * side, -1.0f);
    std::vector<int> seen(std::size_t(side), 0);
    lod_errors(g.heights(), strips, [&](int r0, int r1, const float* v) {
        EXPECT_LE(0, r0);
        EXPECT_LT(r0, r1);
        EXPECT_LE(r1, side);
        std::memcpy(&e[std::size_t(r0) * side], v, std::size_t(r1 - r0) * side * sizeof(float));
        for (int r = r0; r < r1; ++r) ++seen[std::size_t(r)];
    });
    for (int r = 0; r < side; ++r) EXPECT_EQ(seen[std::size_t(r)], 1) << "row " << r;
    return e;
}

// One strip, every level on it.
constexpr LodStrips whole{1 << 30, 1 << 30};

void expect_same_bits(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
    ASSERT_EQ(a.size(), b.size());
    std::size_t differ = 0, first = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::bit_cast<std::uint32_t>(a[i]) != std::bit_cast<std::uint32_t>(b[i]) && differ++ == 0) first = i;
    EXPECT_EQ(differ, 0u) << what << ": first at " << first << ": " << a[first] << " vs " << b[first];
}

}  // namespace

TEST(TerrainLodStrips, EqualTheWholeSquareBitForBit) {
    const int sizes[][2] = {{2, 2}, {3, 2}, {5, 9}, {17, 17}, {33, 20}, {37, 23}, {64, 65}, {100, 61}, {129, 129}, {131, 70}};
    const LodStrips cuts[] = {{1, 2}, {1, 4}, {2, 2}, {3, 8}, {4, 2}, {5, 16}, {8, 4}, {16, 8}, {16, 32}, {64, 2}, {512, 32}};
    unsigned seed = 1;
    for (const auto& s : sizes)
        for (const double holes : {0.0, 0.01, 0.08}) {
            const Grid g = random_grid(s[0], s[1], holes, seed++);
            const std::vector<float> ref = errors(g, whole);
            for (const LodStrips& cut : cuts) {
                const std::string what = std::to_string(s[0]) + "x" + std::to_string(s[1]) + " holes " +
                                         std::to_string(holes) + " strips " + std::to_string(cut.strip_rows) + "/" +
                                         std::to_string(cut.fine_side);
                expect_same_bits(errors(g, cut), ref, what.c_str());
            }
        }
}

TEST(TerrainLodStrips, ErrorsAreFiniteInsideAndInfiniteAtPadding) {
    // 37 x 23 nodes in a 65^2 square: a node with padding in its 3x3 square must split (+inf);
    // a node whose diamond holds only valid nodes has a finite error; the square's corners 0.
    const Grid g = random_grid(37, 23, 0.0, 7);
    const std::vector<float> e = errors(g, {4, 4});
    const int side = 65;
    EXPECT_EQ(e[0], 0.0f);
    EXPECT_EQ(e[std::size_t(side) * side - 1], 0.0f);
    EXPECT_TRUE(std::isinf(e[std::size_t(22) * side + 40]));  // padding column
    EXPECT_TRUE(std::isinf(e[std::size_t(22) * side + 36]));  // next to the padding
    EXPECT_TRUE(std::isfinite(e[std::size_t(3) * side + 5])); // a level-2 node inside
    EXPECT_GT(e[std::size_t(3) * side + 5], 0.0f);
}

TEST(TerrainLodStrips, BuildTerrainLodKeepsTheWholeSquaresErrors) {
    // build_terrain_lod (default strips) on a grid large enough for several strips and upper
    // levels: the same errors as the whole square settled at once on the DEM's nodes, and every
    // padding node's +inf there but the square's corners' (no triangle's split vertex: their
    // errors are never asked for), which TerrainLod does not store.
    Grid g = random_grid(1100, 700, 0.002, 99);
    Terrain t;
    t.cols = g.cols, t.rows = g.rows, t.xy_unit = 1.0;
    t.pos.resize(t.size()), t.valid = g.valid;
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c)
            t.pos[t.index(c, r)] = glm::vec3(float(c), float(-r), g.valid[t.index(c, r)] ? g.z[t.index(c, r)] : 0.0f);
    const TerrainLod lod = build_terrain_lod(t);
    const std::vector<float> ref = errors(g, whole);
    const std::size_t side = std::size_t(lod.side());
    std::vector<float> dem;
    std::size_t padding = 0, finite = 0;
    for (std::size_t r = 0; r < side; ++r)
        for (std::size_t c = 0; c < side; ++c) {
            const float e = ref[r * side + c];
            if (c < std::size_t(t.cols) && r < std::size_t(t.rows)) {
                dem.push_back(e);
                continue;
            }
            ++padding;
            const bool corner = (c == 0 || c == side - 1) && (r == 0 || r == side - 1);  // never split: never asked
            finite += !corner && !(std::isinf(e) && e > 0.0f);
        }
    EXPECT_EQ(padding, side * side - t.size());
    EXPECT_EQ(finite, 0u) << "padding nodes whose error is not +inf";
    expect_same_bits(std::vector<float>(lod.error.begin(), lod.error.end()), dem, "build_terrain_lod");
    EXPECT_EQ(lod.error_at(1100, 3), std::numeric_limits<float>::infinity());
    EXPECT_EQ(lod.error_at(5, 700), std::numeric_limits<float>::infinity());
}

TEST(TerrainLodStrips, RefusesStripsThatAreNotPowersOfTwo) {
    const Grid g = random_grid(9, 9, 0.0, 3);
    EXPECT_THROW(lod_errors(g.heights(), {4, 3}, [](int, int, const float*) {}), std::invalid_argument);
    EXPECT_THROW(lod_errors(g.heights(), {0, 4}, [](int, int, const float*) {}), std::invalid_argument);
}

TEST(TerrainLodStrips, MemoryFollowsTheStripsNotTheSquare) {
    // 11687 x 9976 nodes, a padded side of 16385: a strip of 512 rows and 49 either side (13 B a
    // padded node: 130 MB), the 513 rows every 32 (4 B: 33.6 MB) and the 1025^2 nodes every 16
    // (13 B: 13.7 MB), against 14 B per padded node (3.76 GB) for the whole square.
    const double side = 16385.0;
    EXPECT_NEAR(lod_errors_bytes(11687, 9976), 13.0 * side * 610 + 4.0 * side * 513 + 13.0 * 1025 * 1025, 1.0);
    EXPECT_LT(lod_errors_bytes(11687, 9976), 0.05 * 14.0 * side * side);
    // a square that fits under two fine levels is settled whole
    EXPECT_EQ(lod_errors_bytes(30, 20), 13.0 * 33 * 33);
}
