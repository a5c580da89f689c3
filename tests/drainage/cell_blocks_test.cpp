// CellBlocks (src/drainage/cell_blocks.hpp): each block filled once whatever the threads asking,
// blocks of different stripes filled at the same time, and a block whose fill throws left
// unfilled for the next asker.
#include "drainage/cell_blocks.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace penink {
namespace {

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
