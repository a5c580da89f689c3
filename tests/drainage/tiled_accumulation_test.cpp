// Flow accumulation a band of rows at a time (Barnes 2017 on row bands) is accumulate_flow's on
// the whole grid, cell for cell, and the basins by bands label_basins': D8 directions of random surfaces with pits (outlets inside), long
// paths that cross band edges up and down, and nodata; band heights of 1 row to the whole grid,
// 1 and 3 threads, and over 1 to 4 ranks (threads with the same messages); a cycle is refused.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "drainage/d8.hpp"
#include "drainage/flow_network.hpp"
#include "drainage/tiled_accumulation.hpp"

namespace penink {
namespace {

struct Dirs {
    int cols = 0, rows = 0;
    std::vector<std::uint8_t> dir, valid;
};

// D8 of a surface that meanders (paths that cross rows back and forth) with noise (pits: outlets
// inside the grid) and nodata holes.
Dirs random_dirs(int cols, int rows, std::uint32_t seed, bool holes) {
    Dirs d{cols, rows, {}, std::vector<std::uint8_t>(std::size_t(cols) * rows, 1)};
    std::vector<float> z(d.valid.size());
    std::uint32_t s = seed;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            s = s * 1664525u + 1013904223u;
            const std::size_t i = std::size_t(r) * cols + c;
            z[i] = float(0.3 * c + 8.0 * std::sin(r * 0.7 + c * 0.05) + 3.0 * std::sin(c * 0.4)) + float(s >> 24) / 64.0f;
            if (holes && (s >> 8) % 97 == 0) d.valid[i] = 0;
        }
    d.dir = d8_directions(z, {cols, rows, d.valid.data()}, 1.0, 1.0, nullptr, false);
    return d;
}

DirRowReader rows_of(const Dirs& d) {
    return [&d](int y0, int y1, std::uint8_t* dir, std::uint8_t* valid) {
        const std::size_t b = std::size_t(y0) * d.cols, e = std::size_t(y1) * d.cols;
        std::copy(d.dir.begin() + std::ptrdiff_t(b), d.dir.begin() + std::ptrdiff_t(e), dir);
        std::copy(d.valid.begin() + std::ptrdiff_t(b), d.valid.begin() + std::ptrdiff_t(e), valid);
    };
}

CellWords whole(const Dirs& d) {
    FlowNetwork net;
    accumulate_flow(d.dir, {d.cols, d.rows, d.valid.data()}, net);
    return net.acc;
}

TEST(TiledAccumulation, EqualsTheWholeGridsAccumulation) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        const Dirs d = random_dirs(37 + int(seed) * 11, 41 + int(seed) * 3, seed, seed % 2 == 0);
        const CellWords expected = whole(d);
        std::size_t crossing = 0;  // paths that leave a band of 7 rows upwards
        for (std::size_t i = 0; i < d.dir.size(); ++i)
            if (d.dir[i] && d8_dr[d8_index(d.dir[i])] < 0 && (i / d.cols) % 7 == 0) ++crossing;
        EXPECT_GT(crossing, 5u) << seed;
        for (const int band_rows : {1, 2, 3, 7, d.rows})
            for (const int threads : {1, 3}) {
                std::vector<std::uint32_t> got;
                int next = 0;
                tiled_accumulation(
                    {d.cols, d.rows, band_rows}, rows_of(d),
                    [&](int y0, int y1, const std::uint32_t* acc) {
                        ASSERT_EQ(y0, next);
                        next = y1;
                        got.insert(got.end(), acc, acc + std::size_t(y1 - y0) * d.cols);
                    },
                    threads);
                ASSERT_EQ(next, d.rows);
                for (std::size_t i = 0; i < got.size(); ++i)
                    ASSERT_EQ(got[i], expected[i]) << "seed " << seed << ", bands of " << band_rows << ", cell " << i;
            }
    }
}

// Over 1 to 4 ranks (threads with the same messages), rank 0 alone writing, the accumulation,
// the basins and the Strahler order are the whole grid's.
TEST(TiledAccumulation, DistributedOverRanksIsTheWholeGrids) {
    const Dirs d = random_dirs(90, 61, 9, true);
    FlowNetwork net;
    accumulate_flow(d.dir, {d.cols, d.rows, d.valid.data()}, net);
    label_basins(d.dir, {d.cols, d.rows, d.valid.data()}, net);
    using Pass = void (*)(const FillBands&, const DirRowReader&, const AccRowWriter&, Ranks&, int);
    const std::vector<std::pair<Pass, std::vector<std::uint32_t>>> passes = {
        {distributed_accumulation, {net.acc.begin(), net.acc.end()}},
        {distributed_basins, {net.basin.begin(), net.basin.end()}},
        {distributed_strahler, {net.order.begin(), net.order.end()}}};
    for (std::size_t k = 0; k < passes.size(); ++k)
        for (const int ranks : {1, 2, 3, 4})
            for (const int band_rows : {4, 13}) {
                std::vector<std::uint32_t> got;
                std::mutex m;
                run_thread_ranks(ranks, [&](Ranks& r) {
                    passes[k].first({d.cols, d.rows, band_rows}, rows_of(d),
                                    [&](int, int y1, const std::uint32_t* v) {
                                        const std::lock_guard<std::mutex> lock(m);
                                        ASSERT_EQ(r.rank(), 0);
                                        got.insert(got.end(), v, v + (std::size_t(y1) * d.cols - got.size()));
                                    },
                                    r, 1 + r.rank() % 2);
                });
                ASSERT_EQ(got, passes[k].second) << "pass " << k << ", " << ranks << " ranks, bands of " << band_rows;
            }
}

// Basins by bands are label_basins' labels: outlets numbered in row-major order across the bands,
// every cell labelled with the outlet its path ends at, paths crossing band edges either way.
TEST(TiledAccumulation, BasinsAreTheWholeGridsLabels) {
    for (std::uint32_t seed = 11; seed <= 14; ++seed) {
        const Dirs d = random_dirs(50 + int(seed) * 7, 45, seed, seed % 2 == 1);
        FlowNetwork net;
        label_basins(d.dir, {d.cols, d.rows, d.valid.data()}, net);
        ASSERT_GT(net.outlet.size(), 20u);
        for (const int band_rows : {1, 2, 5, 9, d.rows})
            for (const int threads : {1, 2}) {
                std::vector<std::uint32_t> got;
                tiled_basins(
                    {d.cols, d.rows, band_rows}, rows_of(d),
                    [&](int, int y1, const std::uint32_t* labels) {
                        got.insert(got.end(), labels, labels + (std::size_t(y1) * d.cols - got.size()));
                    },
                    threads);
                ASSERT_EQ(got.size(), net.basin.size());
                for (std::size_t i = 0; i < got.size(); ++i)
                    ASSERT_EQ(got[i], net.basin[i]) << "seed " << seed << ", bands of " << band_rows << ", cell " << i;
            }
    }
}

// Strahler order by bands is accumulate_flow's: orders of 3 and more, whose junctions lie in other
// bands than their sources.
TEST(TiledAccumulation, StrahlerOrderIsTheWholeGridsOrder) {
    for (std::uint32_t seed = 21; seed <= 26; ++seed) {
        const Dirs d = random_dirs(60 + int(seed) * 5, 50 + int(seed) % 3 * 9, seed, seed % 2 == 1);
        FlowNetwork net;
        accumulate_flow(d.dir, {d.cols, d.rows, d.valid.data()}, net);
        EXPECT_GE(*std::max_element(net.order.begin(), net.order.end()), 3) << seed;
        for (const int band_rows : {1, 2, 3, 8, d.rows})
            for (const int threads : {1, 2}) {
                std::vector<std::uint32_t> got;
                tiled_strahler(
                    {d.cols, d.rows, band_rows}, rows_of(d),
                    [&](int, int y1, const std::uint32_t* order) {
                        got.insert(got.end(), order, order + (std::size_t(y1) * d.cols - got.size()));
                    },
                    threads);
                ASSERT_EQ(got.size(), net.order.size());
                for (std::size_t i = 0; i < got.size(); ++i)
                    ASSERT_EQ(got[i], net.order[i]) << "seed " << seed << ", bands of " << band_rows << ", cell " << i;
            }
    }
}

TEST(TiledAccumulation, ACycleAcrossBandsIsRefused) {
    // four cells turning round a square that straddles the edge of two bands of 2 rows
    Dirs d{4, 4, std::vector<std::uint8_t>(16, 0), std::vector<std::uint8_t>(16, 1)};
    auto at = [&](int c, int r) -> std::uint8_t& { return d.dir[std::size_t(r) * 4 + c]; };
    at(1, 1) = 1, at(2, 1) = 4, at(2, 2) = 16, at(1, 2) = 64;  // E, S, W, N
    EXPECT_THROW(tiled_accumulation({4, 4, 2}, rows_of(d), [](int, int, const std::uint32_t*) {}, 1), Error);
    EXPECT_THROW(tiled_accumulation({4, 4, 4}, rows_of(d), [](int, int, const std::uint32_t*) {}, 1), Error);
    EXPECT_THROW(tiled_basins({4, 4, 2}, rows_of(d), [](int, int, const std::uint32_t*) {}, 1), Error);
    EXPECT_THROW(tiled_strahler({4, 4, 2}, rows_of(d), [](int, int, const std::uint32_t*) {}, 1), Error);
}

}  // namespace
}  // namespace penink
