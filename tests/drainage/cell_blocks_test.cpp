// CellBlocks (src/drainage/cell_blocks.hpp): each block filled once whatever the threads asking,
// blocks of different stripes filled at the same time, and a block whose fill throws left
// unfilled for the next asker; BlockGrid's block of a cell, found without dividing, is the
// division's.
#include "drainage/cell_blocks.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <random>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace penink {
namespace {

// Grids of 1 to 2^32 - 1 cells (the largest whose cells the inverse serves), a few beyond, sides
// powers of two or not: every cell of the small ones, and the first, last and random cells
// (rows' edges among them) of the large ones.
TEST(BlockGrid, BlockOfACellIsTheDivisionsBlock) {
    std::mt19937_64 rng(7);
    auto check = [&](std::size_t cols, std::size_t rows, std::size_t side, std::size_t cell) {
        const BlockGrid grid(cols, rows, side);
        ASSERT_EQ(grid.row_of(cell), cell / cols) << cols << " x " << rows << " cell " << cell;
        ASSERT_EQ(grid.block_of(cell), (cell / cols / side) * grid.across + (cell % cols) / side)
            << cols << " x " << rows << " side " << side << " cell " << cell;
    };
    for (std::size_t cols : {1, 2, 3, 7, 16, 17, 255, 256, 257})
        for (std::size_t rows : {1, 2, 5, 33})
            for (std::size_t side : {1, 2, 3, 16, 100, 128})
                for (std::size_t cell = 0; cell < cols * rows; ++cell) check(cols, rows, side, cell);
    const std::uint64_t most = 0xffffffffu;  // cells a grid may have for the inverse
    const std::vector<std::pair<std::size_t, std::size_t>> large{
        {11687, 9976}, {65535, 65537}, {65536, 65535}, {3, most / 3}, {most / 2, 2}, {most, 1},
        {46341, 92681}, {100000, 100000}, {1u << 20, 1u << 13}, {(1u << 20) + 1, 4096}};
    for (const auto& [cols, rows] : large)
        for (std::size_t side : {1, 64, 128, 256, 300}) {
            const std::size_t n = cols * rows;
            for (std::size_t cell : {std::size_t(0), n - 1, cols - 1, cols, n - cols, n / 2}) check(cols, rows, side, cell);
            for (int k = 0; k < 2000; ++k) {
                const std::size_t r = rng() % rows, c = rng() % cols;
                check(cols, rows, side, r * cols + c);
                if (c == 0 && r > 0) check(cols, rows, side, r * cols - 1);
            }
        }
}

TEST(CellBlocks, EveryBlockIsFilledOnceWhateverTheThreads) {
    const BlockGrid grid(300, 200, 16);  // 19 x 13 blocks, the last ones cut
    std::vector<std::atomic<int>> fills(grid.count());
    std::vector<int> cell(grid.cols * grid.rows, -1);
    CellBlocks blocks(grid, [&](std::size_t b) {
        fills[b].fetch_add(1);
        grid.each_cell(b, [&](std::size_t i, std::size_t) { cell[i] = int(b); });
    });
    std::atomic<int> early{0};  // cells read before their block was filled
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (std::size_t k = 0; k < cell.size(); ++k) {  // each thread its own order of the cells
                const std::size_t i = (k * 7919 + std::size_t(t) * 1009) % cell.size();
                blocks.need(i);
                if (cell[i] != int(grid.block_of(i))) early.fetch_add(1);
            }
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(early.load(), 0);
    for (std::size_t b = 0; b < grid.count(); ++b) EXPECT_EQ(fills[b].load(), 1) << b;
    EXPECT_EQ(blocks.filled(), grid.count());
}

// Two blocks (of different stripes) filled by two threads: each fill waits, up to 10 s, for the
// other to start; with one lock for all blocks the second could start only after the first ended.
TEST(CellBlocks, BlocksOfDifferentStripesAreFilledAtOnce) {
    const BlockGrid grid(64, 64, 16);
    std::mutex m;
    std::condition_variable cv;
    int inside = 0;
    bool met = true;
    CellBlocks blocks(grid, [&](std::size_t) {
        std::unique_lock<std::mutex> lock(m);
        ++inside;
        cv.notify_all();
        if (!cv.wait_for(lock, std::chrono::seconds(10), [&] { return inside == 2; })) met = false;
    });
    std::thread a([&] { blocks.need(0); }), b([&] { blocks.need(grid.cols * 16); });  // blocks 0 and 4
    a.join(), b.join();
    EXPECT_TRUE(met);
    EXPECT_EQ(blocks.filled(), 2u);
}

TEST(CellBlocks, ABlockWhoseFillThrowsIsFilledByTheNextAsker) {
    const BlockGrid grid(32, 32, 16);
    int calls = 0;
    CellBlocks blocks(grid, [&](std::size_t) {
        if (++calls == 1) throw std::runtime_error("cannot read");
    });
    EXPECT_THROW(blocks.need(5), std::runtime_error);
    EXPECT_EQ(blocks.filled(), 0u);
    blocks.need(5);
    blocks.need(6);  // the same block: filled already
    EXPECT_EQ(calls, 2);
    EXPECT_EQ(blocks.filled(), 1u);
}

}  // namespace
}  // namespace penink
