// Depression filling of a grid too large to hold, a band of rows at a time (Barnes 2016,
// "Parallel Priority-Flood depression filling for trillion cell digital elevation models", with
// row bands for tiles): the same filled surface as priority_flood_fill (priority_flood.hpp) on
// the whole grid, bit for bit, holding a few bands, their edge rows and the label graph.
//
// Survey (one pass over the grid, bands on several threads): each band is read with one row more
// on each side where the grid has one and flooded on its own (band_flood.hpp: the grid's
// boundary cells and the band's edge rows as seeds, each cell labelled with the seed it drains
// to); it keeps the spills between its labels and the labels, local levels and valid flags of its
// first and last rows. Solve: the spills across each pair of neighbouring bands from those rows,
// then every label's water level W over the label graph (a priority-flood from the ocean).
// Finish (a second pass): each band read and flooded again exactly as before, each cell's level
// max(local level, W(label)), the band's rows handed over in row order.
// Reading twice instead of storing a band's labels and levels keeps the disk untouched; the
// flood is the cheap part of a pass over a DEM that GDAL decodes.
// Grid: row-major, row 0 north, z local metres (nodata cells' z handed back as read).
// The survey and finish of a band depend on nothing but the band (finish: and the water levels),
// so they may run anywhere: on other threads, or on other processes that send their surveys to
// one that solves (the distributed build).
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/ranks.hpp"
#include "drainage/band_flood.hpp"
#include "drainage/priority_flood.hpp"

namespace penink {

// Rows [y0, y1) of the grid: heights (local metres) and valid flags (1 = data), row-major, cols a
// row, into z and valid. May be called from several threads unless the caller serialises it
// (tiled_priority_flood does).
using FillRowReader = std::function<void(int y0, int y1, float* z, std::uint8_t* valid)>;
// The filled heights of rows [y0, y1) (valid flags beside them), called band after band in row
// order.
using FillRowWriter = std::function<void(int y0, int y1, const float* filled, const std::uint8_t* valid)>;

// The bands of a grid of `rows` rows, `band_rows` rows each (the last one shorter).
struct FillBands {
    int cols = 0, rows = 0, band_rows = 1;
    int count() const { return (rows + band_rows - 1) / band_rows; }
    int first_row(int b) const { return b * band_rows; }
    int end_row(int b) const { return std::min(rows, (b + 1) * band_rows); }
};

// What the survey of one band keeps: its number, fill counts, the spills between its labels, and
// the labels, local levels and valid flags of its first and last rows (cols each).
struct BandSurvey {
    int band = 0;
    FillStats stats;
    std::vector<std::pair<std::uint64_t, float>> spills;  // flood::Spills' entries, key order
    std::vector<std::uint32_t> first_labels, last_labels;
    std::vector<float> first_levels, last_levels;
    std::vector<std::uint8_t> first_valid, last_valid;
};

// The rows of a band of about 4 M cells of a grid `cols` wide, in whole strips of `strip` rows (at
// least one strip): the band height a fill by bands starts from (a few hundred MiB in flight).
int fill_band_rows_of_cells(int cols, int strip);

// Bytes one band in flight holds at most (its window's heights, flags, levels, labels and the
// flood's queues for every cell), for choosing band_rows against a memory budget.
std::uint64_t fill_band_bytes(int cols, int band_rows);

// Floods band b on its own (read through `read`).
BandSurvey survey_fill_band(const FillBands& bands, int b, const FillRowReader& read);

// Every label's water level from the surveys of all bands (any order, each band once).
std::vector<float> fill_water_levels(const FillBands& bands, const std::vector<BandSurvey>& surveys);

// Band b's filled heights into `filled` and its valid flags into `valid` ((end_row - first_row) *
// cols each); returns the cells raised.
std::size_t finish_fill_band(const FillBands& bands, int b, const FillRowReader& read, const std::vector<float>& water,
                             std::vector<float>& filled, std::vector<std::uint8_t>& valid);

struct TiledFillStats {
    int bands = 0;
    std::size_t raised = 0;   // cells the fill raised
    std::size_t labels = 0;   // watersheds the bands' edge seeds started
    std::size_t spills = 0;   // spills between labels within the bands
    std::uint64_t band_bytes = 0;  // fill_band_bytes of one band
};

// The whole fill: surveys on up to `threads` threads (0: the hardware's, at most 16; the reads
// one at a time), the water levels, then the bands finished `threads` at a time and written in
// row order. `progress(done, total)` after each band of either pass (total: twice the bands).
TiledFillStats tiled_priority_flood(const FillBands& bands, const FillRowReader& read, const FillRowWriter& write,
                                    int threads = 0, const std::function<void(int, int)>& progress = {});

// The same fill over the ranks of a distributed run (core/ranks.hpp): band b surveyed and finished
// by rank b % size on up to `threads` threads, the surveys sent to rank 0, which solves the water
// levels and broadcasts them, and the finished bands sent to rank 0, which alone calls `write`,
// in row order (its own bands made meanwhile). Every rank reads its own bands through `read`.
// Rank 0's stats are the whole fill's; progress(done, total) on rank 0 alone. The surveys and
// bands travel as bytes (encode_band_survey; a message of another grid is refused).
TiledFillStats distributed_priority_flood(const FillBands& bands, const FillRowReader& read, const FillRowWriter& write,
                                          Ranks& ranks, int threads = 1,
                                          const std::function<void(int, int)>& progress = {});

// A survey as bytes and back (decode throws std::runtime_error on a message that is not a survey
// of a band of `bands`).
std::vector<std::uint8_t> encode_band_survey(const BandSurvey& s);
BandSurvey decode_band_survey(const FillBands& bands, std::span<const std::uint8_t> bytes);

}  // namespace penink
