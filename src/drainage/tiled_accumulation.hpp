// Flow accumulation of a grid too large to hold, a band of rows at a time (Barnes 2017, "Parallel
// non-divergent flow accumulation for trillion cell digital elevation models on desktops or
// clusters", with row bands for tiles): the accumulation accumulate_flow (flow_network.hpp)
// gives the whole grid, cell for cell, holding a few bands, their edge rows and a graph of them.
//
// Survey (bands on several threads): each band's directions are read and its cells accumulated
// counting only the cells of the band upstream (the cell itself included); a cell of its first or
// last row (a perimeter cell) keeps that local accumulation, its direction and its link: the
// perimeter cell where its flow path leaves the band (itself when it points out of the band; none
// when the path ends at an outlet inside). Solve: over the perimeter cells of all bands, in the
// order of the flow (a topological walk; the flow has no cycle), each one's total is its local
// accumulation plus the inflow of the perimeter cells linked to it, and each one's inflow the
// totals of the cells of other bands pointing at it. Finish: each band accumulated again with
// every perimeter cell's inflow added where the cell is, written in row order.
// Basins the same way (tiled_basins): each band counts its outlets and tells, for each perimeter
// cell, the outlet of the band its path ends at, if any; the solve numbers the outlets across
// the bands in row-major order and labels each perimeter cell by following exits from band to
// band; the finish labels each band's cells by their paths.
// Directions: ESRI D8 codes (d8.hpp), 0 at outlets and invalid cells; a valid cell points at a
// valid cell of the grid. Accumulation: u32, 0 at invalid cells.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/ranks.hpp"
#include "drainage/tiled_fill.hpp"

namespace penink {

// Rows [y0, y1) of the directions and valid flags (row-major, cols a row).
using DirRowReader = std::function<void(int y0, int y1, std::uint8_t* dir, std::uint8_t* valid)>;
// The accumulation of rows [y0, y1), band after band in row order.
using AccRowWriter = std::function<void(int y0, int y1, const std::uint32_t* acc)>;

// What the survey of one band keeps of its first and last rows (one row where the band has one):
// each perimeter cell's local accumulation, direction and link (perimeter_node of the cell, or
// -1: its path ends inside the band), and where the path ends inside the band, that outlet's rank
// among the band's outlets in row-major order (-1 elsewhere); and the band's outlets (valid cells
// of code 0).
struct AccSurvey {
    int band = 0;
    std::uint64_t outlets = 0;
    std::vector<std::uint32_t> acc;  // first row, then the last row where it is another
    std::vector<std::uint8_t> dir, valid;
    std::vector<std::int64_t> link, outlet;
};

// The perimeter cells of `bands`: the first and last rows of every band, numbered row by row.
struct AccPerimeter {
    explicit AccPerimeter(const FillBands& bands);
    // Node of cell (c, r) of a perimeter row, -1 for a row that is none.
    std::int64_t node(int c, int r) const;
    std::size_t nodes() const { return rows.size() * std::size_t(cols); }
    int cols = 0;
    std::vector<int> rows;        // the perimeter rows, increasing
    std::vector<int> row_index;   // grid row -> index in rows, -1
};

AccSurvey survey_accumulation_band(const FillBands& bands, int b, const DirRowReader& read);
// Each perimeter node's inflow from other bands, from the surveys of all bands (any order, each
// once). Throws Error("drainage", "", "flow directions contain a cycle", internal) when the
// perimeter's flow has one.
std::vector<std::uint64_t> accumulation_inflows(const FillBands& bands, const std::vector<AccSurvey>& surveys);
// Band b's accumulation with the inflows (rows of the band, cols each).
void finish_accumulation_band(const FillBands& bands, int b, const DirRowReader& read,
                              const std::vector<std::uint64_t>& inflow, std::vector<std::uint32_t>& acc);

// Basins by bands (label_basins' labels, flow_network.hpp: outlets numbered 1, 2, ... in
// row-major order, every cell labelled with its path's outlet): from the surveys, each band's
// first outlet number less one and each perimeter node's label (0 for invalid cells); then band b's
// labels (rows of the band, cols each).
struct PerimeterBasins {
    std::vector<std::uint64_t> first_outlet;  // per band: outlets of the bands above it
    std::vector<std::uint32_t> label;         // per perimeter node
};
PerimeterBasins perimeter_basins(const FillBands& bands, const std::vector<AccSurvey>& surveys);
void finish_basin_band(const FillBands& bands, int b, const DirRowReader& read, const PerimeterBasins& basins,
                       std::vector<std::uint32_t>& labels);
// The whole labelling, on up to `threads` threads, written in row order.
void tiled_basins(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads = 0);

// Strahler order by bands (accumulate_flow's net.order): a band's order at a cell depends on the
// orders entering its edge cells, so its survey keeps the band's paths from its edge cells
// contracted: the edge cells and the cells where two such paths meet (OrderSurvey's nodes), each
// with the fold (push_order) of its upstream cells that no edge cell drains through, and the
// order that reaches its next node as a function of its own (a table; above the table the order
// passes unchanged). The solve walks those nodes of all bands in flow order; each band's finish
// folds into each edge cell the orders of the cells of other bands pointing at it.
struct OrderSurvey {
    int band = 0;
    std::vector<std::int64_t> cell;     // band cells of the nodes (row-major in the band)
    std::vector<std::uint8_t> pending;  // fold of their upstream orders no edge cell reaches
    std::vector<std::uint8_t> dir;      // their directions
    std::vector<std::int32_t> down;     // the next node on the path, -1: none
    std::vector<std::uint32_t> table_at;   // each node's table in `tables`: [table_at[k], table_at[k + 1])
    std::vector<std::uint8_t> tables;      // order reaching `down` for this node's order 0, 1, ...
};
OrderSurvey survey_order_band(const FillBands& bands, int b, const DirRowReader& read);
// Per perimeter node, the fold of the orders of the cells of other bands pointing at it.
std::vector<std::uint8_t> perimeter_order_inflows(const FillBands& bands, const std::vector<OrderSurvey>& surveys);
void finish_order_band(const FillBands& bands, int b, const DirRowReader& read, const std::vector<std::uint8_t>& inflow,
                       std::vector<std::uint8_t>& order);
// The whole order, written as u32 in row order.
void tiled_strahler(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads = 0);

// The whole accumulation, surveys and finishes on up to `threads` threads (0: the hardware's; the
// reads one at a time), written in row order.
void tiled_accumulation(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads = 0);

// The same over the ranks of a distributed run (tiled_fill.hpp's distributed_priority_flood's
// pattern: band b on rank b % size, rank 0 solves, broadcasts the inflows and writes).
void distributed_accumulation(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, Ranks& ranks,
                              int threads = 1);
// Basins and Strahler order over ranks alike.
void distributed_basins(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, Ranks& ranks,
                        int threads = 1);
void distributed_strahler(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, Ranks& ranks,
                          int threads = 1);

}  // namespace penink
