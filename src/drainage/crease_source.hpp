// What building crease tiles (crease_tiles.hpp) reads of a drainage build, stored so that a render
// builds the creases a frame needs without computing the network again: the drainage grid's fine
// nodes' elevations and valid mask, the resolved flow directions, and the tiles' index (tile
// side, the stems' sources, box and bounds, each tile's reach box). The accumulation, Strahler orders
// and basins follow from the directions in one pass each (network_of_directions: accumulate_flow
// and label_basins, the build's own functions, so the same arrays); the grid's other fields
// (size, factor, spacing, origin, the coarse nodes' x, y, mask and heights, the affine grid) are
// stored too, so the creases are built from these bytes alone, on the unexaggerated DEM.
// Coding (encode_crease_source): the three arrays cut in blocks of 2^16 nodes, each block coded
// on its own by core/block_codec.hpp (elevations as floats differenced once along the block,
// the mask and directions as bytes: deflate), the source cells as deltas (deflated u32), the
// boxes as floats, the stems' bounds (StemBound) in blocks of 2^16 stems, each as ten byte planes
// (x0 and y0 each minus the stem before's, x1 - x0, y1 - y0, length; low bytes, then high ones),
// deflated. Lossless: decoding gives the arrays and the index bit for bit.
// (coarse x, y as float pairs differenced twice, coarse heights like z, the coarse mask as bytes).
// Layout (little-endian): u32 cols, rows, i32 factor, f64 dx, dy, origin x, y, i32 coarse cols,
// rows, u32 has_affine, f64 gt[6], f64 unit, i32 col0, row0, u32 side, u32 tiles, f32 x 4 stems'
// box (lo, hi), tiles x f32 x 4 reach boxes, u64 sources, u32 coded bytes + the coded source
// deltas, u64 stems, u32 blocks, blocks x u32 coded sizes, the coded bound blocks, then for z,
// valid, dir, coarse_xy, coarse_valid, coarse_z: u64 elements (the coarse
// ones may be 0), u32 blocks, blocks x u32 coded sizes, the coded blocks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "drainage/crease_tiles.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/flow_network.hpp"

namespace penink {

// g.z, g.valid (g.cols x g.rows), dir and the index, coded (blocks coded on all cores).
std::vector<std::uint8_t> encode_crease_source(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                               const CreaseTileIndex& index);

// Decodes `size` bytes written by encode_crease_source into g (every field encode_crease_source
// reads), dir and index; false (nothing promised of the outputs) when they are not such bytes:
// sizes that do not agree, cut short, trailing bytes, a block that does not decode, counts or
// source cells out of range.
// With arrays = false only g's scalar fields (size, factor, spacing, origin, affine grid) and the
// index are decoded, the arrays checked for their sizes and left empty (a render whose tiles are
// all read from their files needs no more).
bool decode_crease_source(const std::uint8_t* data, std::size_t size, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index, bool arrays = true);

// The accumulation, orders, in-degrees, basins and outlets of the flow directions `dir` on g's
// valid nodes (accumulate_flow and label_basins, one beside the other).
FlowNetwork network_of_directions(const DrainageGrid& g, const std::vector<std::uint8_t>& dir);

}  // namespace penink
