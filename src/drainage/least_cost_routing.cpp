#include "drainage/least_cost_routing.hpp"

#include <bit>
#include <cmath>

namespace penink {

namespace {

// Neighbours in GRASS r.watershed's visiting order S, N, W, E, NE, SW, SE, NW, as indices k of
// d8_dc/d8_dr (ESRI code order E, SE, S, SW, W, NW, N, NE).
constexpr int visit_order[8] = {2, 6, 4, 0, 7, 3, 1, 5};

enum CellState : std::uint8_t { fresh = 0, queued = 1, worked = 2, nodata = 3 };

// Min-priority queue on (elevation, insertion counter): a 4-ary heap of 16-byte entries whose
// key packs an order-preserving image of the float's bits above the counter, so one unsigned
// compare orders by elevation and then oldest first.
class SearchQueue {
public:
    explicit SearchQueue(std::size_t reserve) { heap_.reserve(reserve); }
    bool empty() const { return heap_.empty(); }
    void push(float z, std::uint32_t cell) {
        heap_.push_back({(std::uint64_t(ordered_bits(z)) << 32) | counter_++, cell});
        sift_up(heap_.size() - 1);
    }
    std::uint32_t pop() {
        const std::uint32_t top = heap_.front().cell;
        const Entry last = heap_.back();
        heap_.pop_back();
        if (!heap_.empty()) sift_down(last);
        return top;
    }

private:
    struct Entry {
        std::uint64_t key;
        std::uint32_t cell;
    };
    // -0 and +0 map to one key (as float comparison treats them); negatives below positives.
    static std::uint32_t ordered_bits(float z) {
        const std::uint32_t b = std::bit_cast<std::uint32_t>(z + 0.0f);
        return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
    }
    void sift_up(std::size_t i) {
        const Entry e = heap_[i];
        while (i > 0) {
            const std::size_t p = (i - 1) / 4;
            if (heap_[p].key <= e.key) break;
            heap_[i] = heap_[p];
            i = p;
        }
        heap_[i] = e;
    }
    // Moves `e` into the hole at the root, down to where its smallest child is not smaller.
    void sift_down(const Entry& e) {
        const std::size_t n = heap_.size();
        std::size_t i = 0;
        for (;;) {
            const std::size_t first = 4 * i + 1;
            if (first >= n) break;
            std::size_t best = first;
            const std::size_t end = first + 4 < n ? first + 4 : n;
            for (std::size_t ch = first + 1; ch < end; ++ch)
                if (heap_[ch].key < heap_[best].key) best = ch;
            if (e.key <= heap_[best].key) break;
            heap_[i] = heap_[best];
            i = best;
        }
        heap_[i] = e;
    }
    std::vector<Entry> heap_;
    std::uint32_t counter_ = 0;
};

// The search state: directions being assigned, per-cell state and the queue.
class LeastCostSearch {
public:
    LeastCostSearch(const std::vector<float>& z, const GridShape& shape, double dx, double dy)
        : z_(z), g_(shape), off_(d8_offsets(shape)), dx_(dx), dy_(dy), dir_(shape.size(), 0),
          state_(shape.size()), queue_(std::size_t(2) * (shape.cols + shape.rows) + 16) {
        for (int k = 0; k < 8; ++k) dist_[k] = d8_dc[k] && d8_dr[k] ? std::hypot(dx, dy) : d8_dc[k] ? dx : dy;
        for (std::size_t i = 0; i < g_.size(); ++i) state_[i] = g_.valid[i] ? fresh : nodata;
    }

    std::vector<std::uint8_t> run() {
        seed();
        while (!queue_.empty()) visit(queue_.pop());
        return std::move(dir_);
    }

private:
    // Boundary cells in row-major order: they drain off the grid unless redirected.
    void seed() {
        for (int r = 0; r < g_.rows; ++r)
            for (int c = 0; c < g_.cols; ++c) {
                const std::size_t i = std::size_t(r) * g_.cols + c;
                if (state_[i] == fresh && is_boundary_cell(g_, c, r)) state_[i] = queued, queue_.push(z_[i], std::uint32_t(i));
            }
    }

    void visit(std::size_t c) {
        state_[c] = worked;
        const int r = int(c / std::size_t(g_.cols)), col = int(c % std::size_t(g_.cols));
        const bool inner = r > 0 && r < g_.rows - 1 && col > 0 && col < g_.cols - 1;
        const float zc = z_[c];
        double slope[8] = {-1, -1, -1, -1, -1, -1, -1, -1};  // -1: off the grid, nodata or popped
        for (const int k : visit_order) {
            if (!inner && !on_grid(r + d8_dr[k], col + d8_dc[k])) continue;
            const std::size_t n = std::size_t(std::ptrdiff_t(c) + off_[k]);
            const std::uint8_t s = state_[n];
            if (s == worked || s == nodata) continue;
            slope[k] = z_[n] > zc ? (double(z_[n]) - zc) / dist_[k] : 0.0;
            const bool draining_seed = s == queued && dir_[n] == 0;  // a seed still draining off the grid
            if (s == queued && !draining_seed) continue;
            if (d8_dc[k] && d8_dr[k] && slope[k] > 0 && diagonal_biased(c, n, k, slope)) continue;
            const std::uint8_t toward_c = std::uint8_t(1u << ((k + 4) & 7));
            if (draining_seed) {
                if (slope[k] > 0) dir_[n] = toward_c;  // redirected inward, only from lower ground
                continue;
            }
            state_[n] = queued, dir_[n] = toward_c;
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
    std::vector<std::uint8_t> dir_, state_;
    SearchQueue queue_;
};

}  // namespace

std::vector<std::uint8_t> least_cost_directions(const std::vector<float>& z, const GridShape& shape,
                                                double dx, double dy) {
    return LeastCostSearch(z, shape, dx, dy).run();
}

}  // namespace penink
