// Flow accumulation, Strahler order and basins on resolved D8 directions (Mower, "Concurrent Drainage Network Rendering", sec. 3):
// accumulated flow = inflow + 1 per point (the point counts itself), computed in O(n) by a
// topological walk (in-degree counting, no recursion); Strahler (1957) order per point; basins
// labelled by outlet (a valid cell with code 0: it drains off the grid or is a kept pit), basin
// total = accumulation at its outlet, normalised flow = accumulation / basin total.
#pragma once
#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include "drainage/cell_blocks.hpp"
#include "drainage/d8.hpp"

namespace penink {

struct FlowNetwork {
    CellWords acc;     // points draining through each cell (incl. itself); 0 invalid
    CellBytes order;   // Strahler order (1 at sources); 0 invalid
    CellWords basin;   // basin id 1..B; 0 invalid
    std::vector<std::uint32_t> outlet;  // outlet cell of basin b at outlet[b - 1], in index order
    CellBytes indeg;   // inflow_counts of the directions (kept for the branches)
    // One bit a cell (bit i % 64 of word i / 64): set where the cell is the main upstream cell of
    // the junction it drains into (main_upstream_bits, draped_lines.hpp); empty until found, when
    // the stems' walks find it at each junction they reach.
    std::vector<std::uint64_t> mains;
    // Once keep_normalised_flow ran: each cell's normalised_flow as float bits (0 invalid), in
    // acc's storage; acc, basin and outlet then empty.
    CellWords flow;
    // Where indeg, order and flow hold only the blocks filled so far (a network decoded from a
    // crease source, crease_source.hpp: a walk asks for each cell it reaches, need(i), before it
    // reads the cell's in-degree, order or flow); none: they hold every cell's.
    std::shared_ptr<CellBlocks> blocks;
};

// The network as the creases' walks read it (draped_lines.cpp: orders, in-degrees, mains and each
// cell's flow normalised by its basin's): acc and basin (8 B a cell) replaced by `flow` (4 B, the
// same floats as normalised_flow gives), computed in acc's place. Nothing when already done.
void keep_normalised_flow(FlowNetwork& net);

// A cell's Strahler order from its upstream cells' orders, folded one by one into a pending byte
// (0 at first; it holds (max upstream order << 1) | (two or more at that max)): final_order gives
// 1 without any, the max where one has it, the max + 1 where two or more do.
inline void push_order(std::uint8_t& pending, std::uint8_t upstream) {
    const int m = pending >> 1;
    if (upstream > m) pending = std::uint8_t(upstream << 1);
    else if (upstream == m) pending |= 1;
}
inline std::uint8_t final_order(std::uint8_t pending) {
    const int m = pending >> 1;
    return std::uint8_t(m == 0 ? 1 : m + (pending & 1));
}

// In-degree (number of valid neighbours draining into the cell) of every cell.
CellBytes inflow_counts(const std::vector<std::uint8_t>& dir, const GridShape& g);
// inflow_counts' value at cell i alone: its neighbours whose direction points at it.
inline std::uint8_t inflow_count(const GridShape& g, const std::uint8_t* dir, std::size_t i) {
    const int c = int(i % std::size_t(g.cols)), r = int(i / std::size_t(g.cols));
    std::uint8_t n = 0;
    for (int k = 0; k < 8; ++k) {
        const int mc = c - d8_dc[k], mr = r - d8_dr[k];
        if (mc >= 0 && mr >= 0 && mc < g.cols && mr < g.rows && dir[std::size_t(mr) * std::size_t(g.cols) + std::size_t(mc)] == std::uint8_t(1u << k)) ++n;
    }
    return n;
}

// Fills net.acc, net.order (reusing their storage) and net.indeg. Throws penink::Error("drainage", "",
// "flow directions contain a cycle", internal) when some cell never reaches an outlet.
void accumulate_flow(const std::vector<std::uint8_t>& dir, const GridShape& g, FlowNetwork& net);

// Fills net.basin and net.outlet: outlets numbered in row-major order, every other cell gets the
// label of the outlet its flow path ends in (each path walked at most twice: O(n)). Throws
// like accumulate_flow when the directions contain a cycle (it may run beside it on a thread).
void label_basins(const std::vector<std::uint8_t>& dir, const GridShape& g, FlowNetwork& net);

// A point's normalised flow: its accumulation over its basin's total (the accumulation at the
// basin's outlet), in double, rounded to float (the builder's and the reader's alike).
inline float flow_of(std::uint64_t acc, double basin_total) { return float(double(acc) / basin_total); }

// acc / basin total at cell i (0 for invalid cells); 1 at every outlet.
inline float normalised_flow(const FlowNetwork& net, std::size_t i) {
    if (!net.flow.empty()) return std::bit_cast<float>(net.flow[i]);
    const std::uint32_t b = net.basin[i];
    return b ? flow_of(net.acc[i], net.acc[net.outlet[b - 1]]) : 0.0f;
}

}  // namespace penink
