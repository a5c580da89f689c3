#include "drainage/priority_flood.hpp"

#include <algorithm>
#include <bit>

#include "core/parallel_chunks.hpp"
#include "drainage/radix_heap.hpp"

namespace penink {

namespace {

// A first-in first-out queue in one vector (cheaper than std::queue's deque): reset to its start
// whenever it runs empty.
struct Fifo {
    std::vector<std::uint32_t> cells;
    std::size_t head = 0;
    bool empty() const { return head == cells.size(); }
    void push(std::uint32_t c) { cells.push_back(c); }
    std::uint32_t pop() {
        const std::uint32_t c = cells[head++];
        if (head == cells.size()) cells.clear(), head = 0;
        return c;
    }
};

// z is only read: a raised cell's filled level goes to level[] (float bits) and rides on the pit
// stack with it, so another thread may read z meanwhile.
struct Flood {
    const float* z;
    const GridShape& g;
    std::uint8_t* flags;
    std::uint32_t* level;
    std::array<std::ptrdiff_t, 8> off;
    RadixHeap<std::uint32_t> open;  // exact: every cell queued is at or above the level spilled
    struct Pit {
        std::uint32_t cell;
        float h;  // its filled level
    };
    std::vector<Pit> pit;               // a stack: any order is correct within a level
    Fifo trace;                         // FIFO: climbing breadth-first from the spill reaches a
                                        // cell's lower neighbours first, keeping it off the queue
    FillStats stats;

    void push_open(std::uint32_t i) { open.push(float_order_key(z[i]), i), ++stats.queued; }
    void seed(std::uint32_t i) {
        if (flags[i]) return;
        flags[i] = fill_closed | fill_boundary;
        push_open(i);
    }
    // Closes open neighbour n of a cell at level h: raised to h into the pit stack, or traced.
    void close_from(std::uint32_t n, float h) {
        flags[n] = fill_closed;
        if (z[n] > h) return trace.push(n);
        if (z[n] < h) level[n] = std::bit_cast<std::uint32_t>(h), flags[n] |= fill_raised, ++stats.raised;
        pit.push_back({n, h});
    }
    // Popped from the queue or the pit stack at level h, the lowest open level.
    void spill(std::uint32_t i, float h, bool checked) {
        if (!checked) {
            for (int k = 0; k < 8; ++k) {
                const std::uint32_t n = std::uint32_t(std::ptrdiff_t(i) + off[k]);
                if (!flags[n]) close_from(n, h);
            }
            return;
        }
        const int c = int(i % std::uint32_t(g.cols)), r = int(i / std::uint32_t(g.cols));
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc < 0 || nr < 0 || nc >= g.cols || nr >= g.rows) continue;
            const std::uint32_t n = std::uint32_t(nr) * std::uint32_t(g.cols) + std::uint32_t(nc);
            if (!flags[n]) close_from(n, h);
        }
    }
    // A traced cell (filled = own z, never on the border): its higher-or-equal open neighbours
    // keep their own z whatever happens later, so they are closed and traced at once; an open
    // lower neighbour could still be reached lower elsewhere, so the cell also waits in the queue.
    void climb(std::uint32_t i) {
        const float h = z[i];
        bool lower = false;
        for (int k = 0; k < 8; ++k) {
            const std::uint32_t n = std::uint32_t(std::ptrdiff_t(i) + off[k]);
            if (flags[n]) continue;
            if (z[n] < h) lower = true;
            else flags[n] = fill_closed, trace.push(n);
        }
        if (lower) push_open(i);
    }
};

void seed_boundary(Flood& f) {
    const GridShape& g = f.g;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (!g.valid[i]) f.flags[i] = fill_closed;  // nodata never floods
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (g.valid[i]) continue;  // valid neighbours of nodata are outlets
        const int c = int(i % std::size_t(g.cols)), r = int(i / std::size_t(g.cols));
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc >= 0 && nr >= 0 && nc < g.cols && nr < g.rows)
                f.seed(std::uint32_t(nr) * std::uint32_t(g.cols) + std::uint32_t(nc));
        }
    }
    for (int c = 0; c < g.cols; ++c)
        f.seed(std::uint32_t(c)), f.seed(std::uint32_t(g.rows - 1) * g.cols + std::uint32_t(c));
    for (int r = 1; r + 1 < g.rows; ++r)
        f.seed(std::uint32_t(r) * g.cols), f.seed(std::uint32_t(r) * g.cols + g.cols - 1);
}

}  // namespace

FillStats priority_flood_levels(const std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                                std::vector<std::uint32_t>& level_bits) {
    flags.assign(g.size(), 0);
    level_bits.resize(g.size());
    Flood f{z.data(), g, flags.data(), level_bits.data(), d8_offsets(g), {}, {}, {}, {}};
    seed_boundary(f);
    for (;;) {
        if (!f.pit.empty()) {
            const Flood::Pit p = f.pit.back();
            f.pit.pop_back();
            f.spill(p.cell, p.h, false);
        } else if (!f.trace.empty()) {
            const std::uint32_t i = f.trace.pop();
            f.climb(i);
        } else if (!f.open.empty()) {
            // the level from the key (no load of z[i], a cache miss in elevation order); every
            // cell on the grid's border is a seed, so only seeds need checked neighbours
            const auto e = f.open.pop();
            f.spill(e.cell, float_of_order_key(e.key), f.flags[e.cell] & fill_boundary);
        } else {
            break;
        }
    }
    return f.stats;
}

bool next_to_raised(const GridShape& g, const std::vector<std::uint8_t>& flags, int c, int r) {
    for (int k = 0; k < 8; ++k) {
        const int nc = c + d8_dc[k], nr = r + d8_dr[k];
        if (nc >= 0 && nr >= 0 && nc < g.cols && nr < g.rows && (flags[std::size_t(nr) * g.cols + nc] & fill_raised))
            return true;
    }
    return false;
}

// column[c]: the raised bit of rows r-1..r+1 in column c, then spread to columns c-1..c+1
// (plain byte loops the compiler vectorises).
void near_raised_row(const GridShape& g, const std::vector<std::uint8_t>& flags, int r,
                     std::vector<std::uint8_t>& column, std::uint8_t* near) {
    const std::size_t w = std::size_t(g.cols);
    const std::uint8_t* row = flags.data() + std::size_t(r) * w;
    const std::uint8_t* above = r > 0 ? row - w : row;
    const std::uint8_t* below = r + 1 < g.rows ? row + w : row;
    column.resize(w + 2);
    column[0] = column[w + 1] = 0;
    for (std::size_t c = 0; c < w; ++c) column[c + 1] = (above[c] | row[c] | below[c]) & fill_raised;
    for (std::size_t c = 0; c < w; ++c) near[c] = column[c] | column[c + 1] | column[c + 2];
}

void swap_raised(std::vector<float>& z, const std::vector<std::uint8_t>& flags, std::vector<std::uint32_t>& bits) {
    parallel_chunks(z.size(), std::size_t(1) << 18, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i)
            if (flags[i] & fill_raised) {
                const std::uint32_t zi = std::bit_cast<std::uint32_t>(z[i]);
                z[i] = std::bit_cast<float>(bits[i]), bits[i] = zi;
            }
    });
}

FillStats priority_flood_fill(std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                              std::vector<std::uint32_t>& orig_bits) {
    const FillStats st = priority_flood_levels(z, g, flags, orig_bits);
    swap_raised(z, flags, orig_bits);
    return st;
}

}  // namespace penink
