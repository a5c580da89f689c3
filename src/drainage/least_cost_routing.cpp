#include "drainage/least_cost_routing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "core/big_allocator.hpp"
#include "drainage/radix_heap.hpp"

namespace penink {

namespace {

// Neighbours in GRASS r.watershed's visiting order S, N, W, E, NE, SW, SE, NW, as indices k of
// d8_dc/d8_dr (ESRI code order E, SE, S, SW, W, NW, N, NE): the orthogonal ones first.
constexpr int visit_order[8] = {2, 6, 4, 0, 7, 3, 1, 5};

enum CellState : std::uint8_t { fresh = 0, queued = 1, worked = 2, nodata = 3 };

// Min-priority queue on (elevation key, insertion order). Most keys go to a FIFO radix heap,
// exact for keys at or above the last key it popped; the few below it (cells inside depressions,
// entered from their spill) wait in a small binary heap on (key, counter), always popped first:
// all its keys lie below every key of the radix heap. One key never lies in both (a key pushed
// to the radix heap is >= last(), which passes it only once all its entries are popped; last()
// never falls), so each part's order among equal keys is their insertion order.
class SearchQueue {
public:
    struct Popped {
        std::uint32_t key, cell;
    };
    bool empty() const { return low_.empty() && radix_.empty(); }
    void push(std::uint32_t key, std::uint32_t cell) {
        if (key < radix_.last()) {
            low_.push_back({(std::uint64_t(key) << 32) | counter_++, cell});
            std::push_heap(low_.begin(), low_.end(), later);
        } else {
            radix_.push(key, cell);
        }
    }
    Popped pop() {
        if (low_.empty()) {
            const auto e = radix_.pop();
            return {e.key, e.cell};
        }
        std::pop_heap(low_.begin(), low_.end(), later);
        const LowEntry e = low_.back();
        low_.pop_back();
        return {std::uint32_t(e.key >> 32), e.cell};
    }
    // The cell the next pop returns unless a lower key is pushed first, when cheap to know
    // (FifoRadixHeap::upcoming; the binary heap's top); else null.
    const std::uint32_t* upcoming() const {
        if (!low_.empty()) return &low_.front().cell;
        const auto* e = radix_.upcoming();
        return e ? &e->cell : nullptr;
    }

private:
    struct LowEntry {
        std::uint64_t key;  // elevation key above the insertion counter
        std::uint32_t cell;
    };
    static bool later(const LowEntry& a, const LowEntry& b) { return a.key > b.key; }
    FifoRadixHeap<std::uint32_t> radix_;
    std::vector<LowEntry> low_;  // binary min-heap of the keys below radix_.last()
    std::uint32_t counter_ = 0;
};

// The search on a copy of the grid framed by one ring of nodata cells (cols + 2 wide), so every
// cell has eight neighbour slots and off-grid ones read as nodata: no bounds checks. key_ holds
// float_order_key of each elevation (integer compares order like the floats; the diagonal check
// turns them back into floats, exactly, -0 as +0, which changes no difference it computes: it
// only subtracts unequal values). One byte per cell holds its state (low 2 bits) and, above,
// 1 + the d8 index of the direction it drains to (0: none yet, off the grid), so one load
// answers both questions: a neighbour byte above `queued` is popped, nodata or already has its
// direction, all passed over alike. The bytes become ESRI codes at the end.
class LeastCostSearch {
public:
    LeastCostSearch(const std::vector<float>& z, const GridShape& shape, double dx, double dy)
        : g_(shape), w_(std::size_t(shape.cols) + 2), dx_(dx), dy_(dy), diag_(std::hypot(dx, dy)) {
        const std::size_t padded = w_ * (std::size_t(shape.rows) + 2);
        if (padded > std::size_t(UINT32_MAX)) throw std::length_error("least-cost search: grid over 2^32 cells");
        for (int k = 0; k < 8; ++k) off_[k] = std::ptrdiff_t(d8_dr[k]) * std::ptrdiff_t(w_) + d8_dc[k];
        key_.resize(padded);
        cell_.resize(padded);
        std::fill_n(key_.begin(), w_, 0u), std::fill_n(key_.end() - std::ptrdiff_t(w_), w_, 0u);
        std::fill_n(cell_.begin(), w_, std::uint8_t(nodata));
        std::fill_n(cell_.end() - std::ptrdiff_t(w_), w_, std::uint8_t(nodata));
        for (int r = 0; r < g_.rows; ++r) {
            const std::size_t i0 = std::size_t(r) * g_.cols, p0 = padded_index(r, 0);
            cell_[p0 - 1] = cell_[p0 + g_.cols] = nodata, key_[p0 - 1] = key_[p0 + g_.cols] = 0;
            frame_row(&z[i0], &g_.valid[i0], g_.cols, &key_[p0], &cell_[p0]);
        }
    }

    std::vector<std::uint8_t> run() {
        seed();
        while (!queue_.empty()) {
            const SearchQueue::Popped c = queue_.pop();
            if (const std::uint32_t* next = queue_.upcoming()) prefetch(*next);
            visit(c.cell, c.key);
        }
        std::vector<std::uint8_t> dir(g_.size());
        for (int r = 0; r < g_.rows; ++r) {
            const std::uint8_t* b = &cell_[padded_index(r, 0)];
            std::uint8_t* d = &dir[std::size_t(r) * g_.cols];
            for (int c = 0; c < g_.cols; ++c) d[c] = b[c] >> 2 ? std::uint8_t(1u << ((b[c] >> 2) - 1)) : 0;
        }
        return dir;
    }

private:
    // One grid row into the frame: keys and states (separate arrays: the loop vectorises).
    static void frame_row(const float* __restrict z, const std::uint8_t* __restrict valid, int cols,
                          std::uint32_t* __restrict key, std::uint8_t* __restrict cell) {
        for (int c = 0; c < cols; ++c) key[c] = float_order_key(z[c]), cell[c] = valid[c] ? fresh : nodata;
    }

    std::size_t padded_index(int r, int c) const { return (std::size_t(r) + 1) * w_ + std::size_t(c) + 1; }

    // Boundary cells (valid, on the grid border or next to nodata: a nodata byte among the eight
    // neighbour slots) in row-major order: they drain off the grid unless redirected. Per row,
    // column_gap[j] says whether padded column j holds nodata in this row or the two beside it;
    // a cell is a boundary cell when its own or an adjacent column's flag is set. Rows whose own
    // and adjacent rows are all data can only have seeds in their first and last column.
    void seed() {
        std::vector<std::uint8_t> gap(std::size_t(g_.rows) + 2, 1);  // per padded row: any nodata inside
        for (int r = 0; r < g_.rows; ++r) {
            const std::uint8_t* row = &cell_[padded_index(r, 0)];
            gap[std::size_t(r) + 1] = std::find(row, row + g_.cols, std::uint8_t(nodata)) != row + g_.cols;
        }
        std::vector<std::uint8_t> column_gap(w_);
        for (int r = 0; r < g_.rows; ++r) {
            const std::size_t p0 = padded_index(r, 0);
            if (!gap[std::size_t(r)] && !gap[std::size_t(r) + 1] && !gap[std::size_t(r) + 2]) {
                seed_if_fresh(p0);
                if (g_.cols > 1) seed_if_fresh(p0 + std::size_t(g_.cols) - 1);
                continue;
            }
            mark_column_gaps(&cell_[p0 - 1 - w_], &cell_[p0 - 1], &cell_[p0 - 1 + w_], w_, column_gap.data());
            for (int c = 0; c < g_.cols; ++c)
                if (column_gap[std::size_t(c)] | column_gap[std::size_t(c) + 1] | column_gap[std::size_t(c) + 2])
                    seed_if_fresh(p0 + std::size_t(c));
        }
    }
    static void mark_column_gaps(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down,
                                 std::size_t w, std::uint8_t* __restrict out) {
        for (std::size_t j = 0; j < w; ++j) out[j] = (up[j] == nodata) | (mid[j] == nodata) | (down[j] == nodata);
    }
    void seed_if_fresh(std::size_t p) {
        if (cell_[p] == fresh) cell_[p] = queued, queue_.push(key_[p], std::uint32_t(p));
    }

    void prefetch(std::size_t p) const {
        for (const std::size_t q : {p - w_, p, p + w_}) {
            __builtin_prefetch(&cell_[q]);
            __builtin_prefetch(&key_[q]);
        }
    }

    // Pops cell p (elevation key zc): neighbours in GRASS r.watershed's order S, N, W, E, then
    // the diagonals NE, SW, SE, NW (indices k of d8_dc/d8_dr, ESRI code order E, SE, S, SW, W,
    // NW, N, NE). All eight state bytes and keys are loaded first, independent loads the CPU
    // overlaps (the cell's rows are mostly not in cache); the visit changes no byte it then reads
    // but each neighbour's own, once, when it reaches it, and the diagonal check only asks
    // whether an orthogonal neighbour is popped, which no step of the visit changes.
    void visit(std::size_t p, std::uint32_t zc) {
        std::uint8_t b[8];
        std::uint32_t zn[8];
        for (int k = 0; k < 8; ++k) {
            b[k] = cell_[std::size_t(std::ptrdiff_t(p) + off_[k])];
            zn[k] = key_[std::size_t(std::ptrdiff_t(p) + off_[k])];
        }
        cell_[p] = std::uint8_t((cell_[p] & ~3u) | worked);
        unsigned open = 0;  // bit j: neighbour visit_order[j] fresh or a seed, the only ones acted on
        for (int j = 0; j < 8; ++j) open |= unsigned(b[visit_order[j]] <= queued) << j;
        for (; open; open &= open - 1) {
            const int j = std::countr_zero(open), k = visit_order[j];
            if (j >= 4 && zn[k] > zc && diagonal_biased(zn[k], zc, k, b, zn)) continue;
            reach(p, zc, k, b[k], zn[k]);
        }
    }

    // Neighbour k of p (state byte b, key zn): a fresh one is queued and drains to p; a queued
    // seed still draining off the grid is redirected to p when it lies higher (slope > 0).
    void reach(std::size_t p, std::uint32_t zc, int k, std::uint8_t b, std::uint32_t zn) {
        if (b > queued) return;
        const std::size_t n = std::size_t(std::ptrdiff_t(p) + off_[k]);
        const std::uint8_t toward_p = std::uint8_t((((k + 4) & 7) + 1) << 2 | queued);
        if (b == fresh) cell_[n] = toward_p, queue_.push(zn, std::uint32_t(n));
        else if (zn > zc) cell_[n] = toward_p;
    }

    // A diagonal neighbour k (key zk > zc: rising) is left for later when one of the orthogonal
    // neighbours o beside it is still unpopped (on the grid, valid, not worked) and it rises more
    // steeply from o than from p. Slopes in double as GRASS's comparison was matched; rise 0
    // (zk <= zo) never exceeds the positive slope.
    bool diagonal_biased(std::uint32_t zk, std::uint32_t zc, int k, const std::uint8_t* b,
                         const std::uint32_t* z) const {
        for (const int o : {(k + 7) & 7, (k + 1) & 7}) {
            if ((b[o] & 3) >= worked || zk <= z[o]) continue;
            const double fn = float_of_order_key(zk);
            const double slope = (fn - float_of_order_key(zc)) / diag_;
            const double spacing = d8_dc[o] ? dy_ : dx_;  // o east/west of p: the diagonal lies north/south of o
            if (slope < (fn - float_of_order_key(z[o])) / spacing) return true;
        }
        return false;
    }

    GridShape g_;
    std::size_t w_;  // padded row length
    std::ptrdiff_t off_[8];
    double dx_, dy_, diag_;
    std::vector<std::uint32_t, UninitAllocator<std::uint32_t>> key_;
    std::vector<std::uint8_t, UninitAllocator<std::uint8_t>> cell_;
    SearchQueue queue_;
};

}  // namespace

std::vector<std::uint8_t> least_cost_directions(const std::vector<float>& z, const GridShape& shape,
                                                double dx, double dy) {
    return LeastCostSearch(z, shape, dx, dy).run();
}

}  // namespace penink
