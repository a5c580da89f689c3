#include "drainage/least_cost_routing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "drainage/radix_heap.hpp"

namespace penink {

namespace {

// Neighbours in GRASS r.watershed's visiting order S, N, W, E, NE, SW, SE, NW, as indices k of
// d8_dc/d8_dr (ESRI code order E, SE, S, SW, W, NW, N, NE).
constexpr int visit_order[8] = {2, 6, 4, 0, 7, 3, 1, 5};

enum CellState : std::uint8_t { fresh = 0, queued = 1, worked = 2, nodata = 3 };

// Min-priority queue on (elevation, insertion counter). The key packs float_order_key of the
// elevation above the counter, so one unsigned compare orders by elevation and then oldest first.
// The search pops mostly upwards, so most keys go to a radix heap, exact for keys at or above the
// last key it popped; the few keys below that (cells inside depressions, entered from their
// spill) wait in a small binary heap, which is always popped first: all its keys lie below every
// key in the radix heap.
class SearchQueue {
public:
    bool empty() const { return low_.empty() && radix_.empty(); }
    void push(float z, std::uint32_t cell) {
        const std::uint64_t key = (std::uint64_t(float_order_key(z)) << 32) | counter_++;
        if (key < radix_.last()) low_.push_back({key, cell}), std::push_heap(low_.begin(), low_.end(), later);
        else radix_.push(key, cell);
    }
    std::uint32_t pop() {
        if (low_.empty()) return radix_.pop().cell;
        std::pop_heap(low_.begin(), low_.end(), later);
        const std::uint32_t cell = low_.back().cell;
        low_.pop_back();
        return cell;
    }

private:
    using Entry = RadixHeap<std::uint64_t>::Entry;
    static bool later(const Entry& a, const Entry& b) { return a.key > b.key; }
    RadixHeap<std::uint64_t> radix_;
    std::vector<Entry> low_;  // binary min-heap of the keys below radix_.last()
    std::uint32_t counter_ = 0;
};

// The search: one byte per cell holds its state (low 2 bits) and, above, 1 + the d8 index of
// the direction it drains to (0: none yet, off the grid), so one load answers both questions;
// the bytes become ESRI codes at the end.
class LeastCostSearch {
public:
    LeastCostSearch(const std::vector<float>& z, const GridShape& shape, double dx, double dy)
        : z_(z), g_(shape), off_(d8_offsets(shape)), dx_(dx), dy_(dy), cell_(shape.size()) {
        for (int k = 0; k < 8; ++k) dist_[k] = d8_dc[k] && d8_dr[k] ? std::hypot(dx, dy) : d8_dc[k] ? dx : dy;
        for (std::size_t i = 0; i < g_.size(); ++i) cell_[i] = g_.valid[i] ? fresh : nodata;
    }

    std::vector<std::uint8_t> run() {
        seed();
        while (!queue_.empty()) visit(queue_.pop());
        for (std::uint8_t& b : cell_) b = b >> 2 ? std::uint8_t(1u << ((b >> 2) - 1)) : 0;
        return std::move(cell_);
    }

private:
    // Boundary cells in row-major order: they drain off the grid unless redirected.
    void seed() {
        for (int r = 0; r < g_.rows; ++r)
            for (int c = 0; c < g_.cols; ++c) {
                const std::size_t i = std::size_t(r) * g_.cols + c;
                if (cell_[i] == fresh && is_boundary_cell(g_, c, r)) cell_[i] = queued, queue_.push(z_[i], std::uint32_t(i));
            }
    }

    void visit(std::size_t c) {
        cell_[c] = std::uint8_t((cell_[c] & ~3u) | worked);
        const int r = int(c / std::size_t(g_.cols)), col = int(c % std::size_t(g_.cols));
        const bool inner = r > 0 && r < g_.rows - 1 && col > 0 && col < g_.cols - 1;
        const float zc = z_[c];
        double slope[8] = {-1, -1, -1, -1, -1, -1, -1, -1};  // -1: off the grid, nodata or popped
        for (const int k : visit_order) {
            if (!inner && !on_grid(r + d8_dr[k], col + d8_dc[k])) continue;
            const std::size_t n = std::size_t(std::ptrdiff_t(c) + off_[k]);
            const std::uint8_t b = cell_[n];
            if ((b & 3) >= worked) continue;  // popped or nodata
            slope[k] = z_[n] > zc ? (double(z_[n]) - zc) / dist_[k] : 0.0;
            if (b != fresh && b != queued) continue;  // queued with a direction: stays
            if (d8_dc[k] && d8_dr[k] && slope[k] > 0 && diagonal_biased(c, n, k, slope)) continue;
            const std::uint8_t toward_c = std::uint8_t((((k + 4) & 7) + 1) << 2 | queued);
            if (b == queued) {  // a seed still draining off the grid: redirected, only from lower ground
                if (slope[k] > 0) cell_[n] = toward_c;
                continue;
            }
            cell_[n] = toward_c;
            queue_.push(z_[n], std::uint32_t(n));
        }
    }

    // A diagonal neighbour n (direction k from c) is left for later when one of c's orthogonal
    // neighbours o beside it is still unpopped (slope >= 0) and n rises more steeply from o than
    // from c.
    bool diagonal_biased(std::size_t c, std::size_t n, int k, const double* slope) const {
        for (const int o : {(k + 7) & 7, (k + 1) & 7}) {
            if (slope[o] < 0) continue;
            const float zo = z_[std::size_t(std::ptrdiff_t(c) + off_[o])];
            const double spacing = d8_dc[o] ? dy_ : dx_;  // o east/west of c: n lies north/south of o
            const double rise = z_[n] > zo ? (double(z_[n]) - zo) / spacing : 0.0;
            if (slope[k] < rise) return true;
        }
        return false;
    }

    bool on_grid(int r, int c) const { return r >= 0 && r < g_.rows && c >= 0 && c < g_.cols; }

    const std::vector<float>& z_;
    GridShape g_;
    std::array<std::ptrdiff_t, 8> off_;
    double dx_, dy_, dist_[8];
    std::vector<std::uint8_t> cell_;
    SearchQueue queue_;
};

}  // namespace

std::vector<std::uint8_t> least_cost_directions(const std::vector<float>& z, const GridShape& shape,
                                                double dx, double dy) {
    return LeastCostSearch(z, shape, dx, dy).run();
}

}  // namespace penink
