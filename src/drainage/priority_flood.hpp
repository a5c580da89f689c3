// Depression filling by Priority-Flood (Barnes, Lehman & Mulla 2014, "Priority-flood: An optimal
// depression-filling and watershed-labeling algorithm", Alg. 2: the epsilon-free variant with a
// plain FIFO "pit" queue): every closed depression is raised to its spill elevation, leaving flats
// that the flat resolution drains. Seeds are the valid boundary cells (grid border or next to
// nodata, see d8.hpp), so every valid cell ends up with a non-ascending path to one of them.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"

namespace penink {

// A cell whose elevation the fill raised, with its elevation before filling.
struct RaisedCell {
    std::uint32_t index;
    float z;
};

// Fills `z` (cols*rows, row-major) in place; appends the raised cells to `raised` (so the caller
// can restore the original surface). Returns the number of cells visited.
std::size_t priority_flood_fill(std::vector<float>& z, const GridShape& g,
                                std::vector<RaisedCell>& raised);

// Puts the original elevations of `raised` back into `z`.
void restore_raised(std::vector<float>& z, const std::vector<RaisedCell>& raised);

}  // namespace penink
