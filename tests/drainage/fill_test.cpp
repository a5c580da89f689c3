// The Zhou et al. (2016) Priority-Flood variant gives exactly the filled surface of the textbook
// Priority-Flood (Barnes et al. 2014, Alg. 1) on random grids with pits, flats and nodata, keeps
// slope cells out of the priority queue, and D8 next to a depression aims into it (the unfilled
// DEM's steepest descent, as GRASS r.watershed) without creating cycles.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <mutex>
#include <queue>

#include <gtest/gtest.h>

#include "core/ranks.hpp"
#include "drainage/banded_fill.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/fill_directions.hpp"
#include "drainage/priority_flood.hpp"
#include "drainage/tiled_fill.hpp"

namespace penink {
namespace {

std::uint64_t splitmix64(std::uint64_t& s) {
    std::uint64_t x = (s += 0x9e3779b97f4a7c15ull);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Reference: every cell through one priority queue, filled = max(own z, level it was reached at).
std::vector<float> reference_fill(std::vector<float> z, const GridShape& g) {
    using Node = std::pair<float, std::uint32_t>;
    std::priority_queue<Node, std::vector<Node>, std::greater<Node>> open;
    std::vector<std::uint8_t> closed(g.size(), 0);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::uint32_t i = std::uint32_t(r * g.cols + c);
            if (g.valid[i] && is_boundary_cell(g, c, r)) closed[i] = 1, open.push({z[i], i});
        }
    while (!open.empty()) {
        const auto [h, i] = open.top();
        open.pop();
        for (int k = 0; k < 8; ++k) {
            const int nc = int(i) % g.cols + d8_dc[k], nr = int(i) / g.cols + d8_dr[k];
            if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
            const std::uint32_t n = std::uint32_t(nr * g.cols + nc);
            if (closed[n] || !g.valid[n]) continue;
            closed[n] = 1;
            z[n] = std::max(z[n], h);
            open.push({z[n], n});
        }
    }
    return z;
}

// Random grid: white noise (many pits) quantised to 4 levels plus a gentle slope (flats), with
// random nodata cells.
DrainageGrid random_grid(int cols, int rows, std::uint64_t seed, int nodata_per_mille) {
    std::vector<float> z(std::size_t(cols) * rows);
    std::vector<std::uint8_t> valid(z.size(), 1);
    for (std::size_t i = 0; i < z.size(); ++i) {
        const std::uint64_t b = splitmix64(seed);
        z[i] = float(b & 3) + 0.5f * float((i % cols) / 7);
        valid[i] = int((b >> 8) % 1000) >= nodata_per_mille;
    }
    return make_regular_grid(cols, rows, 1.0, z, valid);
}

TEST(PriorityFlood, EqualsTheTextbookFillOnRandomGrids) {
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        DrainageGrid g = random_grid(40 + int(seed) * 3, 31 + int(seed), seed, seed % 3 ? 50 : 0);
        const GridShape s{g.cols, g.rows, g.valid.data()};
        const std::vector<float> original = g.z;
        const std::vector<float> expected = reference_fill(g.z, s);
        std::vector<std::uint8_t> flags;
        CellWords orig;
        const FillStats st = priority_flood_fill(g.z, s, flags, orig);
        std::size_t raised = 0;
        for (std::size_t i = 0; i < g.size(); ++i) {
            if (!g.valid[i]) continue;
            ASSERT_EQ(g.z[i], expected[i]) << "seed " << seed << " cell " << i;
            ASSERT_EQ(bool(flags[i] & fill_raised), expected[i] > original[i]);
            if (!(flags[i] & fill_raised)) continue;
            ++raised;
            ASSERT_EQ(std::bit_cast<float>(orig[i]), original[i]);
        }
        EXPECT_GT(raised, 0u);
        EXPECT_EQ(st.raised, raised);
        swap_raised(g.z, flags, orig);
        EXPECT_EQ(g.z, original);
    }
}

TEST(PriorityFlood, SlopeCellsBypassThePriorityQueue) {
    // A plane rising to the north-east: only the border seeds go through the queue.
    const int n = 100;
    std::vector<float> z(n * n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) z[r * n + c] = float(c + (n - r));
    DrainageGrid g = make_regular_grid(n, n, 1.0, z);
    std::vector<std::uint8_t> flags;
    CellWords orig;
    const FillStats st = priority_flood_fill(g.z, {n, n, g.valid.data()}, flags, orig);
    EXPECT_EQ(st.raised, 0u);
    EXPECT_LE(st.queued, std::size_t(4 * n));
    EXPECT_EQ(g.z, z);
}

TEST(PriorityFlood, RimCellsDrainIntoTheDepressionSpillCellsDoNot) {
    // 7x7, walls 20 except the outlet (3,0) = 0; a channel (3,1) = 1, (3,2) = 2 leads to a pit
    // (3,3) = -10 that fills to 2 (its spill is (3,2)). Cell (2,4) = 3 with (2,3) = 2.2: on the
    // filled surface west (drop 0.8) beats south-west (1 / sqrt 2); on the unfilled DEM, as in
    // GRASS r.watershed, south-west into the pit is steepest. The spill cell (3,2) must keep
    // draining west, not back into the pit (which would close a cycle).
    const int n = 7;
    std::vector<float> z(n * n, 20.0f);
    for (int r = 1; r < n - 1; ++r)
        for (int c = 1; c < n - 1; ++c) z[r * n + c] = 10.0f;
    z[3 * n + 0] = 0.0f, z[3 * n + 1] = 1.0f, z[3 * n + 2] = 2.0f, z[3 * n + 3] = -10.0f;
    z[2 * n + 4] = 3.0f, z[2 * n + 3] = 2.2f;
    DrainageGrid g = make_regular_grid(n, n, 1.0, z);
    DrainageResult res = compute_drainage(g);
    EXPECT_EQ(g.z, z);
    EXPECT_EQ(res.stats.filled, 1u);
    EXPECT_EQ(res.dir[2 * n + 4], 8);   // south-west, into the pit
    EXPECT_EQ(res.dir[2 * n + 3], 4);   // south, into the pit
    EXPECT_EQ(res.dir[3 * n + 2], 16);  // the spill drains west
    EXPECT_EQ(res.dir[3 * n + 3], 16);  // the pit (a one-cell flat) drains to its spill
    std::uint64_t total = 0;  // acyclic: everything reaches an outlet
    for (std::uint32_t o : res.net.outlet) total += res.net.acc[o];
    EXPECT_EQ(total, std::uint64_t(n) * n);
    EXPECT_EQ(res.stats.unresolved_flats, 0u);
}


// The queue keys elevations by their bits: below-sea-level grids (negative z, -0 next to +0)
// and widely spread magnitudes must still fill exactly like the textbook algorithm.
TEST(PriorityFlood, EqualsTheTextbookFillAcrossZeroAndMagnitudes) {
    for (std::uint64_t seed = 21; seed <= 26; ++seed) {
        DrainageGrid g = random_grid(37, 29, seed, seed % 2 ? 40 : 0);
        std::uint64_t bits = seed;
        for (std::size_t i = 0; i < g.size(); ++i) {
            const std::uint64_t b = splitmix64(bits);
            const float scale = (b >> 20) % 5 == 0 ? 1000.0f : 0.001f * float(1 + (b >> 24) % 7);
            g.z[i] = (g.z[i] - 3.0f) * scale;
            if ((b >> 30) % 9 == 0) g.z[i] = (b >> 40) % 2 ? -0.0f : 0.0f;
        }
        const GridShape s{g.cols, g.rows, g.valid.data()};
        const std::vector<float> expected = reference_fill(g.z, s);
        std::vector<std::uint8_t> flags;
        CellWords orig;
        priority_flood_fill(g.z, s, flags, orig);
        std::size_t raised = 0;
        for (std::size_t i = 0; i < g.size(); ++i) {
            if (!g.valid[i]) continue;
            ASSERT_EQ(g.z[i], expected[i]) << "seed " << seed << " cell " << i;
            raised += (flags[i] & fill_raised) != 0;
        }
        EXPECT_GT(raised, 10u);
    }
}

// The fill and the directions on two threads (D8 of the original DEM, redone near raised cells)
// give what the fill and then D8 on the filled surface give: z, flags, original bits, directions
// and the set of tied cells, on random grids with pits, ties (4 levels) and nodata.
TEST(FillWithDirections, EqualsFillThenDirections) {
    for (std::uint64_t seed = 31; seed <= 38; ++seed) {
        DrainageGrid a = random_grid(45 + int(seed), 33, seed, seed % 2 ? 60 : 0);
        DrainageGrid b = a;
        const GridShape s{a.cols, a.rows, a.valid.data()};
        std::vector<std::uint8_t> flags_a, flags_b, dir_b;
        CellWords orig_a, orig_b;
        std::vector<std::uint32_t> ties_a, ties_b;
        const FillStats st_a = priority_flood_fill(a.z, s, flags_a, orig_a);
        const std::vector<std::uint8_t> dir_a = d8_directions(a.z, s, a.dx, a.dy, &ties_a);
        CellWords labels;
        const int bands = int(seed % 3) + 1;  // 1: the fill beside D8; 2, 3: banded, D8 after
        RoutingArrays arrays_b{b.z, flags_b, orig_b, dir_b, ties_b};
        const FillStats st_b = fill_with_directions({s, b.dx, b.dy}, arrays_b, labels, bands);
        EXPECT_GT(st_a.raised, 20u);
        EXPECT_EQ(st_b.raised, st_a.raised);
        EXPECT_EQ(b.z, a.z);
        EXPECT_EQ(flags_b, flags_a);
        EXPECT_EQ(dir_b, dir_a) << "seed " << seed << " bands " << bands;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (flags_a[i] & fill_raised) {
                ASSERT_EQ(orig_b[i], orig_a[i]);
            }
        std::sort(ties_a.begin(), ties_a.end()), std::sort(ties_b.begin(), ties_b.end());
        EXPECT_GT(ties_a.size(), 50u);
        EXPECT_EQ(ties_b, ties_a);
    }
}

// A fill made elsewhere (the distributed fill over 1-3 ranks, its rows handed over) gives the
// arrays of the fill made here: the filled z, the fill state (raised, closed, boundary seeds),
// the raised cells' original heights, the directions and the ties, on grids with nodata.
TEST(FillWithDirections, AFillMadeElsewhereGivesTheSameArrays) {
    for (std::uint64_t seed = 31; seed <= 36; ++seed) {
        DrainageGrid a = random_grid(45 + int(seed), 33, seed, seed % 2 ? 60 : 0);
        DrainageGrid b = a;
        const GridShape s{a.cols, a.rows, a.valid.data()};
        std::vector<std::uint8_t> flags_a, flags_b, dir_a, dir_b;
        CellWords orig_a, orig_b, labels;
        std::vector<std::uint32_t> ties_a, ties_b;
        RoutingArrays arrays_a{a.z, flags_a, orig_a, dir_a, ties_a};
        const FillStats st_a = fill_with_directions({s, a.dx, a.dy}, arrays_a, labels, 2);
        const int ranks = int(seed % 3) + 1, band_rows = int(seed % 4) * 4 + 3;
        const ExternalFill elsewhere = [&](const GridShape& g, const std::vector<float>& z, const FillRowWriter& rows) {
            const FillRowReader read = [&](int y0, int y1, float* out, std::uint8_t* valid) {
                std::copy(z.begin() + std::ptrdiff_t(y0) * g.cols, z.begin() + std::ptrdiff_t(y1) * g.cols, out);
                std::copy(g.valid + std::ptrdiff_t(y0) * g.cols, g.valid + std::ptrdiff_t(y1) * g.cols, valid);
            };
            run_thread_ranks(ranks, [&](Ranks& r) {
                distributed_priority_flood({g.cols, g.rows, band_rows}, read, r.rank() == 0 ? rows : FillRowWriter{}, r);
            });
        };
        RoutingArrays arrays_b{b.z, flags_b, orig_b, dir_b, ties_b};
        const FillStats st_b = fill_with_directions({s, b.dx, b.dy}, arrays_b, elsewhere);
        EXPECT_GT(st_a.raised, 20u);
        EXPECT_EQ(st_b.raised, st_a.raised);
        EXPECT_EQ(b.z, a.z);
        EXPECT_EQ(flags_b, flags_a) << "seed " << seed;
        EXPECT_EQ(dir_b, dir_a) << "seed " << seed;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (flags_a[i] & fill_raised) {
                ASSERT_EQ(orig_b[i], orig_a[i]);
            }
        std::sort(ties_a.begin(), ties_a.end()), std::sort(ties_b.begin(), ties_b.end());
        EXPECT_EQ(ties_b, ties_a);
    }
}

// Bands flooded on their own and joined through their labels' water levels give the one-thread
// fill bit for bit, whatever the number of bands: depressions across band rows, nodata on them,
// a plateau of equal cells, and levels -0 / +0; rows of more than 64 cells too (the spill scan
// passes over them 64 at a time).
TEST(BandedFill, EqualsTheOneThreadFill) {
    for (std::uint64_t seed = 51; seed <= 62; ++seed) {
        const int cols = (seed % 2 ? 40 : 150) + int(seed % 7);
        DrainageGrid a = random_grid(cols, 30 + int(seed % 5), seed, seed % 3 ? 80 : 0);
        if (seed % 4 == 0)  // a flat-floored basin straddling the bands' shared rows
            for (int r = 8; r < 22; ++r)
                for (int c = 5; c < 30; ++c) a.z[a.index(c, r)] = r == 8 || r == 21 || c == 5 || c == 29 ? 9.0f : 1.0f;
        if (seed % 5 == 0)
            for (float& v : a.z) v = v < 2.0f ? -0.0f : v - 2.0f;  // -0 and +0 spill levels
        const GridShape s{a.cols, a.rows, a.valid.data()};
        std::vector<std::uint8_t> flags_a, flags_b;
        CellWords level_a, level_b, labels;
        const FillStats st_a = priority_flood_levels(a.z, s, flags_a, level_a);
        for (const int bands : {2, 3, 5, 8}) {
            const FillStats st_b = priority_flood_levels_banded(a.z, s, flags_b, level_b, labels, bands);
            ASSERT_EQ(st_b.raised, st_a.raised) << seed << " " << bands;
            ASSERT_EQ(flags_b, flags_a) << seed << " " << bands;
            for (std::size_t i = 0; i < a.size(); ++i)
                if (flags_a[i] & fill_raised) {
                    ASSERT_EQ(level_b[i], level_a[i]) << seed << " " << bands << " cell " << i;
                }
        }
        EXPECT_GT(st_a.raised, 10u);
    }
}

// A grid's rows read from memory, as a DEM's bands are read from its file.
FillRowReader rows_of(const DrainageGrid& a) {
    return [&a](int y0, int y1, float* z, std::uint8_t* valid) {
        const std::size_t b = std::size_t(y0) * a.cols, e = std::size_t(y1) * a.cols;
        std::copy(a.z.begin() + std::ptrdiff_t(b), a.z.begin() + std::ptrdiff_t(e), z);
        std::copy(a.valid.begin() + std::ptrdiff_t(b), a.valid.begin() + std::ptrdiff_t(e), valid);
    };
}

// Random grids like BandedFill's, plus one where every level is -0 or +0 and one with a
// flat-floored basin straddling several bands' edges.
DrainageGrid tiled_fill_grid(std::uint64_t seed) {
    const int cols = (seed % 2 ? 40 : 150) + int(seed % 7);
    DrainageGrid a = random_grid(cols, 30 + int(seed % 5), seed, seed % 3 ? 80 : 0);
    if (seed % 4 == 0)
        for (int r = 8; r < 22; ++r)
            for (int c = 5; c < 30; ++c) a.z[a.index(c, r)] = r == 8 || r == 21 || c == 5 || c == 29 ? 9.0f : 1.0f;
    if (seed % 5 == 0)
        for (float& v : a.z) v = v < 2.0f ? -0.0f : v - 2.0f;
    return a;
}

// The fill a band at a time gives the one-thread fill's filled surface bit for bit (signed zeros
// included; nodata cells as read), whatever the band height (1 row to the whole grid) and the
// threads, and hands every row over once, in order, with its valid flags.
TEST(TiledFill, EqualsTheOneThreadFill) {
    for (std::uint64_t seed = 51; seed <= 62; ++seed) {
        const DrainageGrid a = tiled_fill_grid(seed);
        std::vector<float> expected = a.z;
        std::vector<std::uint8_t> flags;
        CellWords orig;
        const FillStats one = priority_flood_fill(expected, {a.cols, a.rows, a.valid.data()}, flags, orig);
        ASSERT_GT(one.raised, 10u);
        for (const int band_rows : {1, 2, 3, 7, 16, a.rows}) {
            for (const int threads : {1, 3}) {
                std::vector<float> got;
                std::vector<std::uint8_t> valid;
                int next_row = 0;
                const TiledFillStats st = tiled_priority_flood(
                    {a.cols, a.rows, band_rows}, rows_of(a),
                    [&](int y0, int y1, const float* z, const std::uint8_t* v) {
                        ASSERT_EQ(y0, next_row);
                        next_row = y1;
                        got.insert(got.end(), z, z + std::size_t(y1 - y0) * a.cols);
                        valid.insert(valid.end(), v, v + std::size_t(y1 - y0) * a.cols);
                    },
                    threads);
                ASSERT_EQ(next_row, a.rows);
                ASSERT_EQ(valid, a.valid);
                EXPECT_EQ(st.bands, (a.rows + band_rows - 1) / band_rows);
                EXPECT_EQ(st.raised, one.raised) << seed << " " << band_rows;
                for (std::size_t i = 0; i < a.size(); ++i)
                    ASSERT_EQ(std::bit_cast<std::uint32_t>(got[i]), std::bit_cast<std::uint32_t>(expected[i]))
                        << "seed " << seed << " band rows " << band_rows << " cell " << i;
            }
        }
    }
}

// A distributed fill's contract: bands surveyed in any order (as other processes would, each
// survey sent on its own), the water levels from the surveys in any order, and each band
// finished on its own give the one-thread fill.
TEST(TiledFill, BandsSurveyedAndFinishedApartInAnyOrder) {
    const DrainageGrid a = tiled_fill_grid(60);
    std::vector<float> expected = a.z;
    std::vector<std::uint8_t> flags;
    CellWords orig;
    priority_flood_fill(expected, {a.cols, a.rows, a.valid.data()}, flags, orig);
    const FillBands bands{a.cols, a.rows, 4};
    std::vector<BandSurvey> surveys;
    for (int b = bands.count(); b-- > 0;) surveys.push_back(survey_fill_band(bands, b, rows_of(a)));
    std::swap(surveys[1], surveys[3]);
    const std::vector<float> water = fill_water_levels(bands, surveys);
    for (int b = bands.count(); b-- > 0;) {
        std::vector<float> filled;
        std::vector<std::uint8_t> valid;
        finish_fill_band(bands, b, rows_of(a), water, filled, valid);
        ASSERT_EQ(filled.size(), std::size_t(bands.end_row(b) - bands.first_row(b)) * a.cols);
        for (std::size_t k = 0; k < filled.size(); ++k)
            ASSERT_EQ(std::bit_cast<std::uint32_t>(filled[k]),
                      std::bit_cast<std::uint32_t>(expected[std::size_t(bands.first_row(b)) * a.cols + k]))
                << "band " << b << " cell " << k;
    }
    surveys.pop_back();  // a band missing: refused, not a wrong surface
    EXPECT_THROW(fill_water_levels(bands, surveys), std::invalid_argument);
}

// The fill over the ranks of a distributed run (run as threads with the same messages): rank 0
// alone writes, every row once and in order, the one-thread fill's surface; with 1 to 4 ranks
// of 1 or 2 threads, more ranks than bands included.
TEST(TiledFill, DistributedOverRanksIsTheOneThreadFill) {
    for (const std::uint64_t seed : {52u, 55u, 60u}) {
        const DrainageGrid a = tiled_fill_grid(seed);
        std::vector<float> expected = a.z;
        std::vector<std::uint8_t> flags;
        CellWords orig;
        const FillStats one = priority_flood_fill(expected, {a.cols, a.rows, a.valid.data()}, flags, orig);
        for (const int ranks : {1, 2, 3, 4})
            for (const int band_rows : {3, 8, 40}) {
                const FillBands bands{a.cols, a.rows, band_rows};
                std::vector<float> got;
                int next_row = 0, writers = 0;
                std::size_t raised = 0;
                std::mutex m;
                run_thread_ranks(ranks, [&](Ranks& r) {
                    const TiledFillStats st = distributed_priority_flood(
                        bands, rows_of(a),
                        [&](int y0, int y1, const float* z, const std::uint8_t*) {
                            ASSERT_EQ(r.rank(), 0);
                            ASSERT_EQ(y0, next_row);
                            next_row = y1;
                            got.insert(got.end(), z, z + std::size_t(y1 - y0) * a.cols);
                        },
                        r, 1 + r.rank() % 2);
                    const std::lock_guard<std::mutex> lock(m);
                    if (r.rank() == 0) raised = st.raised, ++writers;
                });
                ASSERT_EQ(writers, 1);
                ASSERT_EQ(next_row, a.rows) << ranks << " ranks, bands of " << band_rows;
                EXPECT_EQ(raised, one.raised);
                for (std::size_t i = 0; i < a.size(); ++i)
                    ASSERT_EQ(std::bit_cast<std::uint32_t>(got[i]), std::bit_cast<std::uint32_t>(expected[i]))
                        << "seed " << seed << ", " << ranks << " ranks, bands of " << band_rows << ", cell " << i;
            }
    }
}

// A survey travels as bytes and comes back the same; a message of another grid or cut short is
// refused, not taken.
TEST(TiledFill, SurveyBytesRoundTripAndForeignOnesAreRefused) {
    const DrainageGrid a = tiled_fill_grid(56);
    const FillBands bands{a.cols, a.rows, 7};
    const BandSurvey s = survey_fill_band(bands, 2, rows_of(a));
    ASSERT_FALSE(s.spills.empty());
    const std::vector<std::uint8_t> bytes = encode_band_survey(s);
    const BandSurvey t = decode_band_survey(bands, bytes);
    EXPECT_EQ(t.band, 2);
    EXPECT_EQ(t.spills, s.spills);
    EXPECT_EQ(t.first_labels, s.first_labels);
    EXPECT_EQ(t.last_levels, s.last_levels);
    EXPECT_EQ(t.last_valid, s.last_valid);
    EXPECT_EQ(t.stats.labels, s.stats.labels);
    EXPECT_THROW(decode_band_survey({a.cols + 1, a.rows, 7}, bytes), std::runtime_error);  // another width
    EXPECT_THROW(decode_band_survey({a.cols, a.rows, 40}, bytes), std::runtime_error);     // band 2 of 1
    EXPECT_THROW(decode_band_survey(bands, std::span(bytes).first(bytes.size() - 1)), std::runtime_error);
}

TEST(PriorityFlood, NearRaisedRowIsTheThreeByThreeBlock) {
    const int cols = 37, rows = 11;
    std::vector<std::uint8_t> valid(std::size_t(cols) * rows, 1), flags(valid.size(), fill_closed);
    std::uint32_t state = 12345;
    for (std::uint8_t& f : flags)  // a sprinkle of raised cells, some on the borders
        if ((state = state * 1664525u + 1013904223u) >> 28 == 0) f |= fill_raised;
    const GridShape g{cols, rows, valid.data()};
    std::vector<std::uint8_t> column, near(static_cast<std::size_t>(cols));
    std::size_t hits = 0;
    for (int r = 0; r < rows; ++r) {
        near_raised_row(g, flags, r, column, near.data());
        for (int c = 0; c < cols; ++c) {
            const bool self = flags[std::size_t(r) * cols + c] & fill_raised;
            ASSERT_EQ(near[std::size_t(c)] != 0, self || next_to_raised(g, flags, c, r)) << c << "," << r;
            hits += near[std::size_t(c)] != 0;
        }
    }
    EXPECT_GT(hits, 0u);
    EXPECT_LT(hits, flags.size());
}

}  // namespace
}  // namespace penink
