// The priority-flood state machine shared by the plain fill (priority_flood.cpp) and the banded
// one (banded_fill.cpp): the queue, the pit stack and the climb of Zhou et al. 2016 over the rows
// [row0, row1) of a grid, optionally labelling every cell with the seed it drains to. Internal to
// src/drainage.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "drainage/priority_flood.hpp"
#include "drainage/radix_heap.hpp"

namespace penink::flood {

// Bit of the fill state the banded fill gives the seeds on its bands' shared rows while it runs
// (cleared before it returns): like boundary cells they need checked neighbours.
inline constexpr std::uint8_t band_edge = 4;

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
    // A band of the banded fill: rows [row0, row1) (checked neighbours stay inside) and each
    // closed cell's label, the seed it drains to (0: a boundary cell of the grid); no labels
    // in the plain fill.
    int row0 = 0, row1 = 0;
    std::uint32_t* label = nullptr;
    // The banded fill's edge seeds are labelled when they leave the queue (label_edge), from
    // next_label on where they start a watershed of their own.
    std::uint32_t next_label = 0;
    static constexpr std::uint32_t unlabelled = ~std::uint32_t(0);

    float local(std::uint32_t n) const { return flags[n] & fill_raised ? std::bit_cast<float>(level[n]) : z[n]; }
    // Edge seed i leaving the queue at its own level h: a valid neighbour in the band already
    // labelled at a local level <= h gives it its label (the first in code order), else it takes a
    // new one. Exact, after Barnes 2016's distributed fill, where only the edges' local minima
    // start watersheds: every cell of i's own label would lie at h or higher, so every spill from
    // it would too, and the spill to that neighbour's label is h; the two labels' water levels
    // are then equal, or both below the local levels of i's cells. Fewer labels, a smaller graph.
    void label_edge(std::uint32_t i, float h) {
        if (label[i] != unlabelled) return;
        const int c = int(i % std::uint32_t(g.cols)), r = int(i / std::uint32_t(g.cols));
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc < 0 || nr < row0 || nc >= g.cols || nr >= row1) continue;
            const std::uint32_t n = std::uint32_t(nr) * std::uint32_t(g.cols) + std::uint32_t(nc);
            if (g.valid[n] && flags[n] && label[n] != unlabelled && !(local(n) > h)) {
                label[i] = label[n];
                return;
            }
        }
        label[i] = next_label++;
    }

    void push_open(std::uint32_t i) { open.push(float_order_key(z[i]), i), ++stats.queued; }
    void seed(std::uint32_t i) {
        if (flags[i]) return;
        flags[i] = fill_closed | fill_boundary;
        if (label) label[i] = 0;
        push_open(i);
    }
    // Closes open neighbour n of a cell at level h (label lab): raised to h into the pit stack, or
    // traced.
    void close_from(std::uint32_t n, float h, std::uint32_t lab) {
        flags[n] = fill_closed;
        if (label) label[n] = lab;
        if (z[n] > h) return trace.push(n);
        if (z[n] < h) level[n] = std::bit_cast<std::uint32_t>(h), flags[n] |= fill_raised, ++stats.raised;
        pit.push_back({n, h});
    }
    // Popped from the queue or the pit stack at level h, the lowest open level.
    void spill(std::uint32_t i, float h, bool checked) {
        const std::uint32_t lab = label ? label[i] : 0;
        if (!checked) {
            for (int k = 0; k < 8; ++k) {
                const std::uint32_t n = std::uint32_t(std::ptrdiff_t(i) + off[k]);
                if (!flags[n]) close_from(n, h, lab);
            }
            return;
        }
        const int c = int(i % std::uint32_t(g.cols)), r = int(i / std::uint32_t(g.cols));
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc < 0 || nr < row0 || nc >= g.cols || nr >= row1) continue;
            const std::uint32_t n = std::uint32_t(nr) * std::uint32_t(g.cols) + std::uint32_t(nc);
            if (!flags[n]) close_from(n, h, lab);
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
            if (z[n] < h) {
                lower = true;
                continue;
            }
            flags[n] = fill_closed, trace.push(n);
            if (label) label[n] = label[i];
        }
        if (lower) push_open(i);
    }
};

// The boundary cells of the grid in rows [f.row0, f.row1) as seeds (label 0): every valid cell on
// the grid's border or next to nodata (is_boundary_cell); nodata closed.
inline void seed_band(Flood& f) {
    const GridShape& g = f.g;
    const std::size_t cols = std::size_t(g.cols);
    for (std::size_t i = std::size_t(f.row0) * cols; i < std::size_t(f.row1) * cols; ++i)
        if (!g.valid[i]) {  // nodata never floods
            f.flags[i] = fill_closed;
            if (f.label) f.label[i] = 0;
        }
    const int m0 = std::max(0, f.row0 - 1), m1 = std::min(g.rows, f.row1 + 1);
    for (std::size_t i = std::size_t(m0) * cols; i < std::size_t(m1) * cols; ++i) {
        if (g.valid[i]) continue;  // valid neighbours of nodata are outlets
        const int c = int(i % cols), r = int(i / cols);
        for (int k = 0; k < 8; ++k) {
            const int nc = c + d8_dc[k], nr = r + d8_dr[k];
            if (nc >= 0 && nr >= f.row0 && nc < g.cols && nr < f.row1) f.seed(std::uint32_t(std::size_t(nr) * cols + nc));
        }
    }
    for (const int r : {0, g.rows - 1})
        if (r >= f.row0 && r < f.row1)
            for (int c = 0; c < g.cols; ++c) f.seed(std::uint32_t(std::size_t(r) * cols + c));
    for (int r = std::max(f.row0, 1); r < std::min(f.row1, g.rows - 1); ++r)
        f.seed(std::uint32_t(std::size_t(r) * cols)), f.seed(std::uint32_t(std::size_t(r) * cols + cols - 1));
}

// Runs the flood until every cell reachable from the seeds is closed.
inline void run(Flood& f) {
    for (;;) {
        if (!f.pit.empty()) {
            const Flood::Pit p = f.pit.back();
            f.pit.pop_back();
            f.spill(p.cell, p.h, false);
        } else if (!f.trace.empty()) {
            const std::uint32_t i = f.trace.pop();
            f.climb(i);
        } else if (!f.open.empty()) {
            // the level from the key (no load of z[i], a cache miss in elevation order); only
            // seeds lie on the grid's (or the band's) border: only they need checked neighbours
            const auto e = f.open.pop();
            const float h = float_of_order_key(e.key);
            if (f.flags[e.cell] & band_edge) f.label_edge(e.cell, h);
            f.spill(e.cell, h, f.flags[e.cell] & (fill_boundary | band_edge));
        } else {
            break;
        }
    }
}

}  // namespace penink::flood
