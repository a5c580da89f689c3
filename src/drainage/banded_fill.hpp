// Depression filling on several threads (Barnes 2016, "Parallel Priority-Flood depression filling
// for trillion cell digital elevation models", adapted to row bands): each band of rows is
// flooded on its own (priority_flood.hpp's flood), seeded by the grid's boundary cells in it and
// by every cell of the rows it shares with a neighbouring band, each cell labelled with the seed
// it drains to. Watersheds of shared-row seeds meet each other, and the grid's boundary
// ("ocean", label 0), at spill elevations: the higher local level of two adjacent cells of
// different labels. The least spill path of every label to the ocean (a priority-flood over the
// small label graph) gives its water level W, and each cell's filled level is
// max(local level, W(label)): exactly the one-thread fill, so the result is the same bits.
// Grid: row-major, row 0 north, z local metres.
#pragma once
#include <cstdint>
#include <vector>

#include "drainage/priority_flood.hpp"

namespace penink {

// What priority_flood_levels gives (flags, level_bits of raised cells, stats.raised; stats.queued
// counts the bands' queues), the rows split into `bands` bands (1: priority_flood_levels itself).
// `labels` is scratch (resized to cols*rows; pass an array a later stage fills anew).
FillStats priority_flood_levels_banded(const std::vector<float>& z, const GridShape& g, std::vector<std::uint8_t>& flags,
                                       CellWords& level_bits, CellWords& labels,
                                       int bands);

// Bands for a grid of `rows` rows on this machine: one per hardware thread, each at least 256 rows.
int fill_bands(int rows);

}  // namespace penink
