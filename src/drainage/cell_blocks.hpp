// Arrays over a grid's cells that hold their values only in the square blocks of cells filled so
// far: what a render reads of a large DEM's drainage to build the crease tiles of one view (the
// network's orders and flows decoded, the nodes' UTM x, y computed), where the stems' walks reach
// and not over the grid (crease_source.hpp). Cells row-major, cols x rows; blocks of side x side
// cells, row-major, the last ones of a row or column cut by the grid; a block's cells row-major
// within it.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>

namespace penink {

struct BlockGrid {
    std::size_t cols = 0, rows = 0, side = 1, across = 0, down = 0;
    BlockGrid() = default;
    BlockGrid(std::size_t c, std::size_t r, std::size_t s)
        : cols(c), rows(r), side(s), across((c + s - 1) / s), down((r + s - 1) / s),
          shift_(s > 0 && (s & (s - 1)) == 0 ? __builtin_ctzll(s) : -1),
          row_inverse_(c > 1 && c <= 0xffffffffu && r <= 0xffffffffu / c ? ~std::uint64_t(0) / c + 1 : 0) {}
    std::size_t count() const { return across * down; }
    // (cell / cols / side) * across + (cell % cols) / side, with no division where it can go
    // without: read for every node a crease's drape touches (CellBlocks::need), where the three
    // 64-bit divisions took a tenth of the crease tiles' time (jacksboro x29's whole view).
    std::size_t block_of(std::size_t cell) const {
        const std::size_t r = row_of(cell), c = cell - r * cols;
        return shift_ >= 0 ? (r >> shift_) * across + (c >> shift_) : r / side * across + c / side;
    }
    // cell / cols: by the multiplicative inverse where every cell index and cols fit 32 bits
    // (Lemire, Kaser & Kurz, "Faster remainder by direct computation": the high 64 bits of
    // ceil(2^64 / cols) * cell are the quotient, exactly, for any 32-bit cell and cols).
    std::size_t row_of(std::size_t cell) const {
        if (row_inverse_) return std::size_t((unsigned __int128)row_inverse_ * cell >> 64);
        return cell / cols;
    }
    // Block b's columns [c0, c1) and rows [r0, r1).
    void span(std::size_t b, std::size_t& c0, std::size_t& c1, std::size_t& r0, std::size_t& r1) const {
        c0 = (b % across) * side, r0 = (b / across) * side;
        c1 = std::min(cols, c0 + side), r1 = std::min(rows, r0 + side);
    }
    std::size_t cells(std::size_t b) const {
        std::size_t c0, c1, r0, r1;
        span(b, c0, c1, r0, r1);
        return (c1 - c0) * (r1 - r0);
    }
    // f(cell, k) for block b's cells in its order (k = 0, 1, ...).
    template <class F> void each_cell(std::size_t b, F&& f) const {
        std::size_t c0, c1, r0, r1, k = 0;
        span(b, c0, c1, r0, r1);
        for (std::size_t r = r0; r < r1; ++r)
            for (std::size_t c = c0; c < c1; ++c) f(r * cols + c, k++);
    }

private:
    int shift_ = -1;                  // log2(side) where side is a power of two
    std::uint64_t row_inverse_ = 0;  // ceil(2^64 / cols) where row_of may use it, else 0
};

// need(i) fills the block holding cell i the first time it is asked for (fill(block), under the
// lock of the block's stripe: blocks of different stripes are filled at once by the threads that
// ask for them, so fill must be safe to call concurrently for different blocks; it throws
// penink::Error when it cannot, the block then left unfilled), so a reader calls it before it
// reads cell i; a block once filled is read by any thread without a lock. With one lock for all
// blocks, the two tiles built side by side (crease_tiles.hpp) waited on each other's fills: the
// heights and x, y of a node block read from the terrain cache and projected, a network block
// decoded (jacksboro x29's whole view, its crease tiles built from the drainage cache: 46-48 s
// with one lock, measured in docs/timings.md).
class CellBlocks {
public:
    CellBlocks(BlockGrid grid, std::function<void(std::size_t block)> fill)
        : grid_(grid), ready_(std::make_unique<std::atomic<std::uint8_t>[]>(grid.count())), fill_(std::move(fill)) {}
    void need(std::size_t i) {
        const std::size_t b = grid_.block_of(i);
        if (ready_[b].load(std::memory_order_acquire)) return;
        const std::lock_guard<std::mutex> lock(stripes_[b % stripes]);
        if (ready_[b].load(std::memory_order_relaxed)) return;
        fill_(b);
        filled_.fetch_add(1, std::memory_order_relaxed);
        ready_[b].store(1, std::memory_order_release);
    }
    const BlockGrid& grid() const { return grid_; }
    std::size_t filled() const { return filled_.load(std::memory_order_relaxed); }  // blocks filled so far

private:
    static constexpr std::size_t stripes = 64;
    BlockGrid grid_;
    std::unique_ptr<std::atomic<std::uint8_t>[]> ready_;  // one a block: 1 once filled
    std::function<void(std::size_t)> fill_;
    std::atomic<std::size_t> filled_{0};
    std::mutex stripes_[stripes];
};

}  // namespace penink
