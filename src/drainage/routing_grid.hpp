// What the priority-flood direction stages pass on, stage to stage (drainage_build.cpp runs them
// in turn: fill_directions.hpp, then depression_drainage.hpp and flat_resolution.hpp, then
// d8_ties.hpp): the grid with its cell spacing, and views of the caller's per-cell arrays that
// each stage reads or changes in place (each stage's comment says which).
// Grid: row-major, row 0 north, dx / dy metres; elevations in metres.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"

namespace penink {

struct RoutingGrid {
    GridShape shape;
    double dx = 0.0, dy = 0.0;  // cell spacing, metres
};

// cols*rows entries each, but `ties`.
struct RoutingArrays {
    std::vector<float>& z;             // elevations; the filled surface once fill_with_directions ran
    std::vector<std::uint8_t>& flags;  // per-cell fill state (priority_flood.hpp) and the later stages' bits
    CellWords& orig_bits;              // the original elevations of the raised cells (float bits; of every cell after break_d8_ties)
    std::vector<std::uint8_t>& dir;    // ESRI D8 codes
    std::vector<std::uint32_t>& ties;  // cells whose steepest neighbours tie (break_d8_ties settles them)
};

}  // namespace penink
