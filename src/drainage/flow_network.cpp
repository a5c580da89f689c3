#include "drainage/flow_network.hpp"

#include <array>
#include <bit>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"

namespace penink {

CellBytes inflow_counts(const std::vector<std::uint8_t>& dir, const GridShape& g) {
    CellBytes indeg(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (dir[i]) ++indeg[d8_target(g, i, dir[i])];
    return indeg;
}

void accumulate_flow(const std::vector<std::uint8_t>& dir, const GridShape& g, FlowNetwork& net) {
    // the in-degree (at most 8) in the low 4 bits, a copy counted down as upstream cells are
    // done in the high 4 bits: all zero again once the walk is through
    net.indeg = inflow_counts(dir, g);
    CellBytes& in = net.indeg;
    for (std::uint8_t& b : in) b = std::uint8_t(b | b << 4);
    net.acc.assign(g.size(), 0);
    net.order.assign(g.size(), 0);
    // raw restrict pointers and a local offset table: the byte stores would otherwise make the
    // compiler reload every vector's data pointer at each step
    std::uint32_t* __restrict acc = net.acc.data();
    std::uint8_t* __restrict order = net.order.data();
    std::uint8_t* __restrict count = in.data();
    const std::uint8_t* __restrict code = dir.data();
    const std::uint8_t* __restrict valid_cell = g.valid;
    const std::array<std::ptrdiff_t, 8> off = d8_offsets(g);
    std::size_t done = 0, valid = 0;
    for (std::size_t s = 0; s < g.size(); ++s) {
        if (!valid_cell[s]) continue;
        ++valid;
        if (count[s] != 0 || acc[s] != 0) continue;  // not a source, or already walked
        for (std::size_t c = s;;) {  // walk down while every upstream cell is done
            acc[c] += 1;
            order[c] = final_order(order[c]);
            ++done;
            if (!code[c]) break;
            const std::size_t d = std::size_t(std::ptrdiff_t(c) + off[std::size_t(d8_index(code[c]))]);
            acc[d] += acc[c];
            push_order(order[d], order[c]);
            count[d] = std::uint8_t(count[d] - 16);
            if (count[d] >> 4) break;
            c = d;
        }
    }
    if (done != valid)
        throw Error("drainage", "", "flow directions contain a cycle", ExitCode::internal);
}

void label_basins(const std::vector<std::uint8_t>& dir, const GridShape& g, FlowNetwork& net) {
    net.basin.assign(g.size(), 0);
    net.outlet.clear();
    for (std::size_t i = 0; i < g.size(); ++i)
        if (g.valid[i] && !dir[i]) {
            net.outlet.push_back(std::uint32_t(i));
            net.basin[i] = std::uint32_t(net.outlet.size());
        }
    std::uint32_t* __restrict basin = net.basin.data();  // as in accumulate_flow
    const std::uint8_t* __restrict code = dir.data();
    const std::uint8_t* __restrict valid = g.valid;
    const std::array<std::ptrdiff_t, 8> off = d8_offsets(g);
    auto next = [&](std::size_t c) { return std::size_t(std::ptrdiff_t(c) + off[std::size_t(d8_index(code[c]))]); };
    std::size_t steps = 0;  // every path is walked at most twice: more means a cycle
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (!valid[i] || basin[i]) continue;
        std::size_t c = i;
        while (!basin[c]) {
            if (++steps > 2 * g.size())
                throw Error("drainage", "", "flow directions contain a cycle", ExitCode::internal);
            c = next(c);
        }
        const std::uint32_t label = basin[c];
        for (c = i; !basin[c]; c = next(c)) basin[c] = label;
    }
}

void keep_normalised_flow(FlowNetwork& net) {
    if (!net.flow.empty() || net.acc.empty()) return;
    std::vector<double> total(net.outlet.size());  // each basin's outlet accumulation, as normalised_flow divides
    for (std::size_t b = 0; b < total.size(); ++b) total[b] = net.acc[net.outlet[b]];
    parallel_chunks(net.acc.size(), std::size_t(1) << 16, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i) {
            const std::uint32_t b = net.basin[i];
            net.acc[i] = std::bit_cast<std::uint32_t>(b ? flow_of(net.acc[i], total[b - 1]) : 0.0f);
        }
    });
    net.flow = std::move(net.acc);
    CellWords().swap(net.acc), CellWords().swap(net.basin);
    std::vector<std::uint32_t>().swap(net.outlet);
}

}  // namespace penink
