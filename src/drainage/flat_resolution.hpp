// Drainage over flats (Barnes, Lehman & Mulla 2014, "An efficient assignment of drainage direction
// over flat surfaces in raster digital elevation models"): each flat (connected cells of equal
// elevation with no downhill neighbour, e.g. a filled depression) gets a combined gradient —
// towards lower terrain (BFS from its low edges, weight 2) minus away from higher terrain (BFS
// from its high edges) — and its cells drain down that gradient, so channels run through the
// middle of valley floors and lakes to the spill point instead of stopping.
// Differences from the paper, same directions: flats are told apart by elevation equality of
// adjacent cells instead of a label raster, the per-flat offset (FlatHeight) is dropped (only
// cells of one flat are compared) and low edges get the lowest mask, so after one scan of the
// direction bytes only flat cells and their edges are touched. The two BFS run at once on two
// threads (each with its own visited bits), then the gradients are combined and the flat cells
// settled in parallel chunks: the same codes as one thread, in any order.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"
#include "drainage/routing_grid.hpp"

namespace penink {

// Bits of `flags` used by resolve_flats (left set); bits 0, 1 and 4 belong to the fill.
inline constexpr std::uint8_t flat_seen_high = 4, flat_seen_low = 8;
inline constexpr std::uint8_t flat_interior = 64;  // a flat interior cell (what resolve_flats gave a code)

// Gives every flat interior cell of arrays.dir (valid, code 0, not a boundary cell) a D8 code, on
// the filled elevations arrays.z. `mask` is a scratch buffer (resized to cols*rows; pass the one
// that later holds basins to save memory), arrays.flags the fill's per-cell state
// (priority_flood.hpp: fill_boundary marks the boundary cells; bits 2, 3 and 6 are set here).
// Returns the number of flat cells that stay without a direction (0 on a filled surface).
// Afterwards `mask` holds, for every cell marked flat_seen_low, its combined gradient as int32
// (INT32_MIN on low edges); flat cells with several neighbours of least gradient are appended to
// arrays.ties, raised cells excepted (break_d8_ties settles them). With raised_too false the cells
// the fill raised keep code 0 (for drain_depressions, which gives every one of them its code, from
// flat_candidates where it keeps the flat's). arrays.orig_bits is not used.
std::size_t resolve_flats(const GridShape& g, RoutingArrays& arrays, CellWords& mask, bool raised_too = true);

// Flat cell i (flat_seen_low set, not a low edge): bit k set for each neighbour k of least
// gradient, from `flags` and `mask` as resolve_flats left them; resolve_flats gave the cell the
// lowest of these codes.
unsigned flat_candidates(const std::vector<float>& z, const GridShape& g,
                         const std::vector<std::uint8_t>& flags,
                         const CellWords& mask, std::size_t i);

}  // namespace penink
