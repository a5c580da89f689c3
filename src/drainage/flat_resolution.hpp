// Drainage over flats (Barnes, Lehman & Mulla 2014, "An efficient assignment of drainage direction
// over flat surfaces in raster digital elevation models"): each flat (connected cells of equal
// elevation with no downhill neighbour, e.g. a filled depression) gets a combined gradient —
// towards lower terrain (BFS from its low edges, weight 2) plus away from higher terrain (BFS from
// its high edges) — and its cells drain down that gradient, so channels run through the middle
// of valley floors and lakes to the spill point instead of stopping.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"

namespace penink {

// Gives every flat interior cell of `dir` (valid, code 0, not a boundary cell) a D8 code, on the
// filled elevations `z`. labels and mask are scratch buffers (resized to cols*rows and zeroed;
// pass the buffers that later hold accumulation and basins to save memory). Returns the number
// of flat cells that stay without a direction (0 on a filled surface).
std::size_t resolve_flats(const std::vector<float>& z, const GridShape& g,
                          std::vector<std::uint8_t>& dir, std::vector<std::uint32_t>& labels,
                          std::vector<std::uint32_t>& mask);

}  // namespace penink
