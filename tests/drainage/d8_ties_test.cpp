// Ties between equally steep neighbours go to the one whose own path gets lower sooner; equal
// paths keep the lowest ESRI code.
#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "drainage/d8_steepest.hpp"
#include "drainage/d8_ties.hpp"
#include "drainage/depression_drainage.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/fill_directions.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/priority_flood.hpp"
#include "drainage/radix_heap.hpp"

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

namespace penink {
namespace {

// The direction stages up to the ties (drainage_build.cpp's priority-flood order) on grid g, the
// arrays as break_d8_ties gets them.
struct BeforeTies {
    DrainageGrid g;
    std::vector<std::uint8_t> flags, dir;
    CellWords orig, mask;
    std::vector<std::uint32_t> ties;
    GridShape shape() const { return GridShape{g.cols, g.rows, g.valid.data()}; }
    RoutingGrid grid() const { return RoutingGrid{shape(), g.dx, g.dy}; }
    RoutingArrays arrays() { return RoutingArrays{g.z, flags, orig, dir, ties}; }
};

BeforeTies before_ties(DrainageGrid grid) {
    BeforeTies s;
    s.g = std::move(grid);
    RoutingArrays a = s.arrays();
    fill_with_directions(s.grid(), a, s.mask);
    drain_rims_into_depressions(s.grid(), a);
    resolve_flats(s.shape(), a, s.mask, false);
    drain_depressions(s.grid(), a, s.mask);
    return s;
}

// The settling as first written, the reference: ties sorted by an indirect comparison of
// (filled, rank, index), duplicates dropped, each cell settled in turn by comparing the full
// `depth`-long path keys of every candidate.
void reference_ties(BeforeTies& s, int depth) {
    const std::vector<float>& filled = s.g.z;
    const GridShape g = s.shape();
    const D8Steps st = d8_steps(g, s.g.dx, s.g.dy);
    auto original = [&](std::size_t n) { return original_z(filled, s.flags, s.orig, n); };
    auto gradient = [&](std::size_t i) { return std::int32_t(s.mask[i]); };
    auto flat_cell = [&](std::size_t i) {
        return (s.flags[i] & flat_seen_low) && !(s.flags[i] & fill_raised) && gradient(i) != INT32_MIN;
    };
    auto rank = [&](std::size_t i) { return flat_cell(i) ? std::int64_t(gradient(i)) - INT32_MIN + 1 : 0; };
    auto before = [&](std::uint32_t a, std::uint32_t b) {
        if (filled[a] != filled[b]) return filled[a] < filled[b];
        const std::int64_t ra = rank(a), rb = rank(b);
        return ra != rb ? ra < rb : a < b;
    };
    auto path_key = [&](std::size_t n, float* key) {
        for (int j = 0; j < depth; ++j) {
            key[j] = original(n);
            if (!s.dir[n]) {
                std::fill(key + j + 1, key + depth, -std::numeric_limits<float>::infinity());
                return;
            }
            n = d8_target(g, n, s.dir[n]);
        }
    };
    std::sort(s.ties.begin(), s.ties.end(), before);
    s.ties.erase(std::unique(s.ties.begin(), s.ties.end()), s.ties.end());
    for (const std::uint32_t i : s.ties) {
        if (s.flags[i] & depression_outflow) continue;
        unsigned set;
        if (flat_cell(i)) {
            set = flat_candidates(filled, g, s.flags, s.mask, i);
        } else {
            const int c = int(i % std::size_t(g.cols)), r = int(i / std::size_t(g.cols));
            const float zi = original(i), level = filled[i];
            const bool raised = s.flags[i] & fill_raised;
            auto ok = [&](std::size_t n) { return raised ? original(n) < zi : filled[n] < level; };
            set = d8_steepest(zi, g, c, r, st, original, ok).steepest;
        }
        if ((set & (set - 1)) == 0) continue;
        std::array<float, 64> best{}, key{};
        std::uint8_t code = 0;
        for (int k = 0; k < 8; ++k) {
            if (!(set >> k & 1)) continue;
            path_key(std::size_t(std::ptrdiff_t(i) + st.off[k]), key.data());
            if (!code || std::lexicographical_compare(key.begin(), key.begin() + depth, best.begin(), best.begin() + depth))
                best = key, code = std::uint8_t(1u << k);
        }
        s.dir[i] = code;
    }
}

// Whole metres: a tilted plane with random steps, plateaus (flats) and pits (depressions), some
// nodata holes; heights around sea level so that -0, 0 and negative levels occur.
DrainageGrid tied_terrain(int cols, int rows, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> noise(-1, 1), pick(0, 99), dc(0, cols - 1), dr(0, rows - 1), size(1, 6);
    std::vector<float> z(std::size_t(cols) * rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            z[std::size_t(r) * cols + c] = std::floor(0.25f * float(c) + 0.1f * float(r) - 6.0f) + float(noise(rng));
    std::vector<std::uint8_t> valid(z.size(), 1);
    for (int k = 0; k < cols * rows / 40; ++k) {  // plateaus, pits, holes
        const int c0 = dc(rng), r0 = dr(rng), w = size(rng), kind = pick(rng);
        const float level = z[std::size_t(r0) * cols + c0];
        for (int r = r0; r < std::min(rows, r0 + w); ++r)
            for (int c = c0; c < std::min(cols, c0 + w); ++c) {
                const std::size_t i = std::size_t(r) * cols + c;
                if (kind < 60) z[i] = level;
                else if (kind < 95) z[i] = level - 3.0f;
                else if (kind < 97) valid[i] = 0;
            }
    }
    for (float& v : z) v = v == 0.0f && pick(rng) < 50 ? -0.0f : v;
    return make_regular_grid(cols, rows, 10.0, z, valid);
}

// Bits that break_d8_ties packs per tie when its order keys fit in one 64-bit word (d8_ties.cpp):
// the span of the ties' filled elevations' order keys less their common low zero bits, of their
// flat ranks (plus one for the D8 cells' 0), of the cell indices, and 8 of candidates.
int packed_bits(const BeforeTies& s) {
    std::uint32_t z_min = UINT32_MAX, z_max = 0, differ = 0;
    std::int64_t rank_min = INT64_MAX, rank_max = INT64_MIN;
    for (const std::uint32_t i : s.ties) {
        const std::uint32_t z = float_order_key(s.g.z[i]);
        z_min = std::min(z_min, z), z_max = std::max(z_max, z), differ |= z ^ float_order_key(s.g.z[s.ties[0]]);
        if ((s.flags[i] & flat_seen_low) && !(s.flags[i] & fill_raised) && std::int32_t(s.mask[i]) != INT32_MIN)
            rank_min = std::min<std::int64_t>(rank_min, std::int32_t(s.mask[i])),
            rank_max = std::max<std::int64_t>(rank_max, std::int32_t(s.mask[i]));
    }
    const int shift = differ ? std::countr_zero(differ) : 0;
    const int rank_bits = rank_max >= rank_min ? std::bit_width(std::uint64_t(rank_max - rank_min + 1)) : 0;
    return std::bit_width((z_max - z_min) >> shift) + rank_bits + std::bit_width(s.g.z.size() - 1) + 8;
}

// Heights with random fractions falling east from 5 m to -5 m, a 130 x 260 plateau at 3.7 m
// whose east side is its exit (flat gradients hundreds apart) and 10 x 10 plateaus at the
// heights around them, either side of 0 m (order keys 32 bits apart).
DrainageGrid wide_key_terrain(int cols, int rows, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> fraction(0.0f, 0.01f);
    std::vector<float> z(std::size_t(cols) * rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const bool plateau = c >= 20 && c < 150 && r >= 20 && r < 280;
            z[std::size_t(r) * cols + c] = plateau ? 3.7f : 5.0f - 10.0f * float(c) / float(cols) + fraction(rng);
        }
    for (int c0 = 160; c0 + 10 < cols; c0 += 20)
        for (int r0 = 20; r0 + 10 < rows; r0 += 40) {
            const float level = z[std::size_t(r0 + 5) * cols + c0 + 5];
            for (int r = r0; r < r0 + 10; ++r)
                for (int c = c0; c < c0 + 10; ++c) z[std::size_t(r) * cols + c] = level;
        }
    return make_regular_grid(cols, rows, 10.0, z);
}

TEST(D8Ties, SettlesLikeTheReferenceOnRandomTiedTerrain) {
    for (unsigned seed = 1; seed <= 7; ++seed) {
        // seed 7: order keys too wide for one word (the ties sorted as key and index pairs)
        const BeforeTies start = before_ties(seed == 7 ? wide_key_terrain(300, 300, seed)
                                                       : tied_terrain(70 + int(seed) * 7, 90 + int(seed) * 5, seed));
        ASSERT_GT(start.ties.size(), 300u);
        if (seed == 7) EXPECT_GT(packed_bits(start), 64);
        else EXPECT_LE(packed_bits(start), 64);
        for (const int depth : {16, 3}) {
            BeforeTies want = start;
            reference_ties(want, depth);
            for (const TieThreads split : {TieThreads{1, 0, 0}, TieThreads{2, depth + 1, depth}, TieThreads{3, 20, 20},
                                            TieThreads{2, 30, 0}, TieThreads{0, 0, 0}}) {
                BeforeTies got = start;
                RoutingArrays a = got.arrays();
                break_d8_ties(got.grid(), a, got.mask, depth, split);
                EXPECT_EQ(got.ties, want.ties) << "seed " << seed << " depth " << depth;
                EXPECT_EQ(got.dir, want.dir) << "seed " << seed << " depth " << depth << " threads " << split.threads
                                             << " strip rows " << split.strip_rows << " segment columns " << split.segment_cols;
            }
            std::size_t changed = 0;
            for (std::size_t i = 0; i < start.dir.size(); ++i) changed += start.dir[i] != want.dir[i];
            EXPECT_GT(changed, 10u) << "the ties must decide something";
        }
    }
}

}  // namespace
}  // namespace penink
