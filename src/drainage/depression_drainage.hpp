// Drainage into and inside filled depressions on the real terrain (as GRASS r.watershed's A*
// search drains them; cf. the breaching/filling hybrids of Lindsay 2016): the rims drain into the
// lake down their original slopes; once the flat resolution has drained
// every filled depression to its spill point over the filled surface, each raised cell with a
// strictly lower neighbour on the ORIGINAL DEM drains to its steepest such neighbour, so streams
// run down the depression's slopes to its low points. The low points (no lower original
// neighbour) keep the flat-resolved path from them to the spill — the depression's outflow,
// marked `depression_outflow` in the fill flags — and every cell on that path keeps its direction.
// No cycle is possible: a lower original neighbour of a raised cell is raised too, steps off the
// outflow paths strictly descend the original DEM until they meet a low point or a path, and a
// path leaves the filled flat to strictly lower ground.
// Grid: row-major, row 0 north, dx / dy metres; elevations in metres.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/d8.hpp"
#include "drainage/routing_grid.hpp"

namespace penink {

// Bit of the fill flags (priority_flood.hpp, flat_resolution.hpp use bits 0..4).
inline constexpr std::uint8_t depression_outflow = 32;

// Rims first (before the flat resolution; matches D8 on the unfilled DEM, as GRASS r.watershed
// does, without creating cycles): every valid, non-raised cell next to a raised cell drains to
// its steepest neighbour measured on the ORIGINAL elevations, chosen among the neighbours
// strictly lower on the FILLED surface, so a slope drains into the lake as on the real terrain
// and a spill cell cannot point back into its own depression. Cells without such a neighbour
// keep code 0. Reads arrays.z (the filled surface), arrays.flags and arrays.orig_bits; re-aims
// arrays.dir; re-aimed cells with tied steepest neighbours are appended to arrays.ties (maybe
// twice).
void drain_rims_into_depressions(const RoutingGrid& g, RoutingArrays& arrays);

// Then inside, after the flat resolution.
// arrays.z: the filled surface; arrays.flags / arrays.orig_bits: the fill's state (fill_raised
// and original elevations of raised cells), the outflow paths marked depression_outflow in
// arrays.flags; `flat_mask`: the flat gradients resolve_flats left; arrays.dir: flat-resolved ESRI
// codes, re-aimed in place. Raised cells whose steepest original descent is tied are appended to
// arrays.ties (those later found on an outflow path are skipped by break_d8_ties). Returns the
// number of cells on outflow paths.
std::size_t drain_depressions(const RoutingGrid& g, RoutingArrays& arrays, const CellWords& flat_mask);

}  // namespace penink
