// Where a stem's built crease can lie, from its network cells alone (before it is traced, smoothed
// or draped: draped_lines.hpp), so that a frame can tell which stems it may need without building
// them. In the drainage grid's index space (c east, r south; fine cells):
// - the centre line S of the trace (fall_line_stems.hpp, step 1) is a Gaussian average of the
//   cells and of their point reflections through the two ends over the kernel's radius
//   (polyline_smoothing.hpp): it lies in the box of those points;
// - every traced vertex lies within the corridor (at most options.max_corridor cells) of S and in
//   the grid's index range, or where the vertex before it lies (a stopped trace), or at its own
//   cell (the source; a stem of fewer than 3 vertices is not traced);
// - ending a stem where it meets its trunk moves vertices onto the stem's own vertices, and the
//   clamp to the whole set's box keeps a vertex inside any box holding its cell.
// So every vertex lies in the box of the cells and reflections grown by max_corridor (+ 1 cell for
// rounding), within the grid. Its plan position is grid_xy_at there, a convex combination of the
// nodes of the grid cell holding it (bilinear at factor 1, the cell triangle's substituted nodes
// at factor > 1): the plan box of the nodes under the index box holds it. PlanBoxes answers that
// on an affine grid from the node range's four corners (the nodes are an affine image of their
// indices), elsewhere from the boxes of 8 x 8 node blocks (a superset: whole blocks).
// A bound of the crease's length at vertical exaggeration e, from the same cells: the trace
// (fall_line_stems.hpp) steps from each vertex as far as the smoothed centre line S does, and S, a
// Gaussian average of the cells' path, is no longer in plan than that path; the drape gives each
// vertex the PN surface's height, which follows the cells' heights; a stem ending where it meets
// its trunk only gets shorter. The exaggerated length of a polyline, the sum of
// sqrt(plan step^2 + e^2 dz^2), is at most its plan length plus e times its vertical travel (the
// sum of |dz|), so the crease's is about at most plan + e rise of the polyline through its cells'
// drainage vertices (x, y from grid_xy, z from g.z): not a proof (a trace drawn back onto its
// corridor, or a drape over a bump between two cells, adds a little), hence the factors
// crease_length_factor and crease_rise_factor, chosen from the largest ratios measured
// (tests/drainage/stem_reach_test.cpp). At e = 2 on a gentle DEM this is near half of max(1, e)
// times the 3-D length.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/drainage_grid.hpp"
#include "drainage/fall_line_stems.hpp"

namespace penink {

struct CellBox {  // index space, fine cells; empty when c1 < c0
    double c0 = 0.0, r0 = 0.0, c1 = -1.0, r1 = -1.0;
};

// The index box holding every vertex of the crease built from a stem with these `n` cells (in
// stem order: network_stems' cells) on `g` with `options` (fall_line_options(g) in the build).
CellBox stem_cell_reach(const std::uint32_t* cells, std::uint32_t n, const DrainageGrid& g, const FallLineOptions& options);

// The plan length and vertical travel (metres, unexaggerated; the sums of the steps' plan lengths
// and of their |dz|) of the polyline through the drainage vertices of a stem's `n` cells
// (grid_xy, g.z), in stem order. `xy`: the cells' x, y as the stems' walk gives them (grid_xy
// rounded to floats), read instead of grid_xy at factor 1, where grid_xy's are those floats (at
// jacksboro x29's 117 M cells grid_xy made again from the rows' samples here was 3 % of the
// index's samples, a sixth of all its grid_xy).
struct StemTravel {
    double plan = 0.0, rise = 0.0;
};
StemTravel stem_cell_travel(const std::uint32_t* cells, std::uint32_t n, const DrainageGrid& g, const glm::vec2* xy = nullptr);
// A built crease's plan length over its cells', at most 1.18 measured over every stem of volcano
// (factors 1 and auto), a DEM with holes and jacksboro (the worst on jacksboro), and its vertical
// travel over its cells' plus crease_rise_slope times their plan length, at most 1.34 (volcano at
// its automatic factor 5: the coarse PN surface bulges between nodes; 1.18 on jacksboro): the
// factors leave a margin of a fifth. The slope term covers stems whose cells are flat (no rise)
// while the drape between them is not (without it, a ratio without bound; with 0.02, 1.74).
inline constexpr double crease_length_factor = 1.5;
inline constexpr double crease_rise_factor = 1.65;
inline constexpr double crease_rise_slope = 0.05;

// What a crease tiles' index (crease_tiles.hpp) keeps of a stem to cull it before it is built,
// in 12 bytes: its reach's plan box on a grid of 65535 steps across the stems' box [lo, hi]
// (StemParts: every crease vertex lies in it), rounded outward, crease_length_factor times the
// cells' plan length and crease_rise_factor times their rise plus crease_rise_slope times the
// plan length,
// each with 8 significant bits (a bfloat16's: the high half of the float), rounded up.
struct StemBound {
    std::uint16_t x0 = 1, y0 = 1, x1 = 0, y1 = 0;  // steps; empty when x1 < x0
    std::uint16_t plan = 0, rise = 0;
    bool operator==(const StemBound&) const = default;
};
// The bound of a stem whose reach's plan box is [reach_lo, reach_hi] and cells' travel `t`.
StemBound stem_bound(glm::vec2 reach_lo, glm::vec2 reach_hi, StemTravel t, glm::vec2 lo, glm::vec2 hi);
// The bound of a stem's built crease line, no looser than its stem's bound `reach` (on the same
// box [lo, hi]): the plan box of its vertices rounded outward, its plan length and its rise (the
// sums of |dxy| and |dz| along it: `t`, unscaled) rounded up, each field the tighter of the two (the
// boxes intersected). Its length bound at any exaggeration holds the line's 3-D length and its box
// every vertex, so a test growing with both (CreaseTiles::LineTest) passes it whenever it passes
// the line, and fails it whenever it fails `reach`.
StemBound stem_line_bound(glm::vec2 box_lo, glm::vec2 box_hi, StemTravel t, const StemBound& reach, glm::vec2 lo,
                          glm::vec2 hi);
// The plan box the bound stands for (holding reach ∩ [lo, hi]; empty, hi < lo, for an empty
// reach), its plan and rise bounds (at least the factors' products above) and its length bound at
// vertical exaggeration e >= 0: plan + e rise.
void stem_bound_box(const StemBound& b, glm::vec2 lo, glm::vec2 hi, glm::vec2& box_lo, glm::vec2& box_hi);
float stem_bound_plan(const StemBound& b);
float stem_bound_rise(const StemBound& b);
double stem_bound_length(const StemBound& b, double e);

// n bounds coded losslessly as twelve byte planes (x0 and y0 each minus the bound before's, x1 -
// x0, y1 - y0, plan, rise; a field's low bytes, then its high ones), deflated; decoding gives
// them bit for bit (false when the bytes do not decode to n).
std::vector<std::uint8_t> encode_stem_bounds(const StemBound* b, std::size_t n);
bool decode_stem_bounds(const std::uint8_t* coded, std::size_t size, StemBound* b, std::size_t n);
// n ascending stem ids coded as the first and each one's step from the one before (u32 bytes),
// deflated; decoding refuses ids that are not strictly ascending.
std::vector<std::uint8_t> encode_stem_ids(const std::uint32_t* ids, std::size_t n);
bool decode_stem_ids(const std::uint8_t* coded, std::size_t size, std::uint32_t* ids, std::size_t n);

// A height (metres, unexaggerated) no draped vertex of `g`'s creases exceeds: the creases are draped
// on the PN-triangle surface of the DEM's nodes (dem_surface.hpp: g.z at factor 1, coarse_z at
// factor > 1), and a PN patch (Vlachos et al. 2001) lies in its control net's hull, whose heights
// are at most its corners' highest plus its longest 3-D edge L (an edge point (2 P_i + P_j -
// w_ij N_i) / 3 with |w_ij| <= L rises at most L / 3 above the corners; the centre point E + (E -
// V) / 2 at most L). So the highest valid node plus the longest edge between valid neighbours (east,
// south, south-east), plus a thousandth of both for the evaluation's rounding and the locator's
// tolerance, bounds them; -inf without a valid node.
float drape_height_top(const DrainageGrid& g);

// Plan boxes (local metres) of index boxes of a grid: the box of every node whose grid cells an
// index point of the box may be interpolated from: the corners of their range on an affine grid,
// else by blocks of 8 x 8 nodes, a range 4 blocks or more across in both directions from the
// boxes of windows of 4 x 4 blocks that cover it (overlapping; made once, rounded outward to
// floats block by block, which gives the same floats: the rounding is monotonic). A stem's reach
// at factor 1 spans about 6 x 6 blocks (the corridor's 21 cells each side): 4 windows instead of
// 36 blocks.
class PlanBoxes {
public:
    explicit PlanBoxes(const DrainageGrid& g);
    // A plan box holding grid_xy_at of every point of `b` (rounded outward to floats), or an
    // empty one (hi < lo) for an empty b.
    void plan_box(const CellBox& b, glm::vec2& lo, glm::vec2& hi) const;

private:
    static constexpr int block = 8, window = 4;
    const DrainageGrid* g_ = nullptr;
    bool affine_ = false, coarse_ = false;
    double factor_ = 1.0;  // fine index / node index
    int cols_ = 0, rows_ = 0, bcols_ = 0, brows_ = 0;  // nodes, blocks
    std::vector<glm::dvec2> lo_, hi_;  // per block (not on an affine grid)
    // per window of blocks [bc, bc + window) x [br, br + window) (those that fit), rounded outward
    std::vector<glm::vec2> window_lo_, window_hi_;
    glm::dvec2 node(int c, int r) const;
};

}  // namespace penink
