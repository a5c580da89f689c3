// What building crease tiles (crease_tiles.hpp) reads of a drainage build, stored so that a render
// builds the creases a frame needs without computing the network again: the drainage grid's fine
// nodes' elevations and valid mask, the resolved flow directions, and the tiles' index (tile
// side, the stems' sources, box and bounds, each tile's reach box, the units' summaries), and the
// network the stems' walks read (code_source_network: the accumulation, basins and Strahler
// orders by square blocks, each basin's total, the junctions' mains), so that a render decodes
// only the blocks its walks reach instead of computing the network from the directions (which a
// source without it still does: network_of_directions, the build's own accumulate_flow and
// label_basins, so the same arrays); the grid's other fields
// (size, factor, spacing, origin, the coarse nodes' x, y, mask and heights, the affine grid) are
// stored too, so the creases are built from these bytes alone, on the unexaggerated DEM.
// Coding (encode_crease_source): the three arrays cut in blocks of 2^16 nodes, each block coded
// on its own by core/block_codec.hpp (elevations as floats differenced once along the block,
// the mask and directions as bytes: deflate), the source cells as deltas (u32, deflated in
// blocks alike), the boxes as floats, the stems' bounds (StemBound) in blocks of 2^16 stems, each
// as twelve byte planes (x0 and y0 each minus the stem before's, x1 - x0, y1 - y0, plan, rise; low
// bytes, then high ones), deflated. Lossless: decoding gives the arrays and the index bit for bit.
// (coarse x, y as float pairs differenced twice, coarse heights like z, the coarse mask as bytes).
// At factor 1 the coarse mask is the fine one (coarse_valid_shared): not stored again.
// At factor 1 the grid's heights and (on a geographic DEM) its nodes' UTM x, y are the DEM's own
// as read_dem gives them: with a DEM reference (a build from a DEM file: drainage_build.cpp) they
// are not stored but the DEM's absolute path, the UTM zone and hemisphere read and a hash of
// the two arrays; decoding reads them from the DEM again (heights only) and refuses them unless
// they hash alike (a DEM changed or gone: the source does not decode).
// Layout (little-endian): u32 cols, rows, i32 factor, f64 dx, dy, origin x, y, i32 coarse cols,
// rows, u32 has_affine, u32 coarse mask shared (1: coarse_valid is valid, stored with 0
// elements), u32 DEM reference (1: then u32 n + n bytes of the DEM's path, i32 UTM zone, u32
// north, u32 blocks of z and their u64 hashes, the same for x, y (DemArraysHash); z and coarse_xy
// stored with 0 elements), f64 gt[6], f64 unit, i32 col0, row0, u32 side, u32 tiles, f32 x 4 stems'
// box (lo, hi), tiles x f32 x 4 reach boxes, f32 z_top, u32 units, units x (u32 tile, level,
// count, f32 x 4 box, u16 plan, rise: CreaseUnit; u32 coded sizes of its ids and of its bounds),
// for the source cells' deltas (u32): u64 elements, u32 blocks, blocks x u32 coded sizes, the
// coded blocks; each unit's stems (ids, stem_reach.hpp encode_stem_ids, then their bounds,
// encode_stem_bounds: a unit decodes alone); then for z, valid, dir, coarse_xy, coarse_valid,
// coarse_z: u64 elements (the coarse ones may be 0), u32 blocks, blocks x u32 coded sizes, the
// coded blocks; then u32 network stored (0 or 1), and when stored: u32 block side, u64 basins, u32
// coded size and the coded totals, the mains' bytes as the arrays above (u64 elements, u32
// blocks, sizes, blocks), u32 blocks, blocks x u32 coded sizes, the coded blocks.
// The arrays may be coded one by one as each becomes final (code_source_array; a build codes
// the grid's while the directions are found, and z and the directions while the ridges are
// draped and the index made) and put together with the index after (assemble_crease_source).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/checked_blocks.hpp"
#include "drainage/crease_tiles.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/flow_network.hpp"

namespace penink {

// The arrays a crease source codes as the build made them (DrainageDb::built_network): what
// decoding it and network_of_directions give again, bit for bit (the network as
// keep_normalised_flow leaves it where load_or_build_drainage keeps it for a render).
struct BuiltNetwork {
    DrainageGrid g;
    std::vector<std::uint8_t> dir;
    FlowNetwork net;
};

// Where a factor-1 grid's heights and node x, y are read again: the DEM file (its absolute
// path, absolute_dem_path) read with heights_only, this UTM zone (0 for a projected DEM) and
// hemisphere.
struct DemHeightsRef {
    std::string path;
    int utm_zone = 0;
    bool north = true;
};
std::string absolute_dem_path(const std::string& path);

// The side (cells) of the square blocks a crease source stores its network by (code_source_network).
inline constexpr int network_block_side = 128;

// What a DEM reference checks the arrays read again by: hash64 of each block of
// network_block_side nodes (BlockGrid order, a block's nodes in its order) of g.z and of
// g.coarse_xy (none where it is empty: an affine grid), so that the heights and x, y a render
// reads and makes where its walks reach are checked block by block.
struct DemArraysHash {
    std::vector<std::uint64_t> z, xy;
    bool operator==(const DemArraysHash&) const = default;
};
DemArraysHash dem_arrays_hash(const DrainageGrid& g);

// g.z, g.valid (g.cols x g.rows), dir and the index, coded (blocks coded on all cores):
// assemble_crease_source of every code_source_array. With `dem` (factor 1 only), z and
// coarse_xy are referred to, not stored.
std::vector<std::uint8_t> encode_crease_source(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                               const CreaseTileIndex& index, const DemHeightsRef* dem = nullptr,
                                               const FlowNetwork* network = nullptr, int network_side = network_block_side);

// A crease source's bytes as its decoders read them: `size` bytes at `data`, in memory, or (with
// `pages`) the database file's, where only the pages need() asks for are readable (read and
// checked by their hash64 the first time: core/checked_blocks.hpp, array 0 of `pages`, pages of
// crease_source_page bytes; throws DamagedBlockError on a damaged page).
struct CreaseSourceBytes {
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
    const CheckedBlocks* pages = nullptr;
    // Where the DEM it refers to is read (DrainageDb::crease_source_dem); empty: the path stored.
    std::string dem = {};
    void need(std::uint64_t at, std::uint64_t n) const;
};
// The bytes of a source held as `bytes`, or, with `pages`, the `size` left in the file; its DEM
// read at `dem` where not empty.
CreaseSourceBytes crease_source_bytes(const std::vector<std::uint8_t>& bytes, const CheckedBlocks* pages,
                                      std::uint64_t size, std::string dem = {});
// A database's (DrainageDb::crease_source, or its pages, and crease_source_dem).
CreaseSourceBytes crease_source_bytes(const DrainageDb& db);
// The page a database file checks its crease source by, and the pages' hash64 (the last one
// short): stored after the source (drainage_db.cpp), they are also what identifies it (the tile
// files' key: stored_creases.hpp).
inline constexpr std::size_t crease_source_page = std::size_t(1) << 16;
std::vector<std::uint64_t> crease_source_page_sums(const std::uint8_t* data, std::size_t n);

// The DEM path a crease source stores ("" when it stores its arrays or does not decode), whatever
// src.dem says.
std::string crease_source_dem(const CreaseSourceBytes& src);
inline std::string crease_source_dem(const std::uint8_t* data, std::size_t size) {
    return crease_source_dem(CreaseSourceBytes{data, size});
}

// The arrays of a crease source in the order it stores them.
enum class SourceArray { z, valid, dir, coarse_xy, coarse_valid, coarse_z };
inline constexpr std::size_t source_array_count = 6;

// One array coded: its element count and its blocks of 2^16 elements, each coded on its own.
struct CodedSourceArray {
    std::uint64_t elements = 0;
    std::vector<std::vector<std::uint8_t>> blocks;
};

// Array `a` of g (dir for SourceArray::dir) coded, its blocks on all cores; reads only that
// array (and, for coarse_valid, g.valid and g.factor).
CodedSourceArray code_source_array(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, SourceArray a);

// The network the stems' walks read (draped_lines.cpp), stored beside the directions so that a
// render builds stems without computing it again, and reads of it only the blocks its walks reach
// (FlowNetwork::blocks, cell_blocks.hpp): each basin's total (the accumulation at its outlet, u32 as
// float bits, encode_floats unchanged), the junctions' mains (FlowNetwork::mains' words as bytes,
// blocks of 2^16 bytes, deflated), and square blocks of network_block_side cells (row-major
// blocks, cells row-major within a block; the last ones cut by the grid: BlockGrid), each coded on
// its own: the cells' (accumulation, basin, order) less what the flow inside the block predicts
// (a valid cell's accumulation 1 + its in-block upstream cells', its Strahler order from theirs,
// its basin its in-block downstream cell's; 0 for an invalid cell), as u32 differences (wrapping)
// in float bits (encode_floats, orders 0): zero but where flow enters the block from outside or
// leaves it, so the network takes 0.16 B a cell (jacksboro refined 29 times, 117 M cells) where the
// values coded as they are took 1.0. Decoding adds them
// back in the block's topological order of its flow (upstream first; basins downstream first),
// from the directions and the mask; a cell's flow is then flow_of(accumulation, its basin's
// total), the floats normalised_flow gives.
struct CodedSourceNetwork {
    int side = network_block_side;
    std::uint64_t basins = 0;
    std::vector<std::uint8_t> totals;
    CodedSourceArray mains;
    std::vector<std::vector<std::uint8_t>> blocks;
};
// net: accumulate_flow and label_basins of the directions `dir` on g's mask, with its mains
// (main_upstream_bits); blocks of `side` cells (1 to 2^15) coded on all cores.
CodedSourceNetwork code_source_network(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                       const FlowNetwork& net, int side = network_block_side);

// The crease source of g's scalars, the coded index (code_crease_index, or coded_crease_tile_index
// a row of tiles at a time) and the coded arrays (code_source_array of each SourceArray, in order):
// the bytes encode_crease_source gives. With `dem`, z and coarse_xy are empty CodedSourceArrays
// and `hashes` is dem_arrays_hash(g).
// With `network`, it is stored after the arrays (else a source without it: a render computes it).
std::vector<std::uint8_t> assemble_crease_source(const DrainageGrid& g, const CodedCreaseIndex& index,
                                                 const std::vector<CodedSourceArray>& arrays,
                                                 const DemHeightsRef* dem = nullptr, const DemArraysHash& hashes = {},
                                                 const CodedSourceNetwork* network = nullptr);

// Decodes `size` bytes written by encode_crease_source into g (every field encode_crease_source
// reads), dir and index; false (nothing promised of the outputs) when they are not such bytes:
// sizes that do not agree, cut short, trailing bytes, a block that does not decode, counts or
// source cells out of range.
// What is decoded: with SourcePart::index only g's scalar fields (size, factor, spacing, origin,
// affine grid) and the index, the arrays checked for their sizes and left empty; with
// SourcePart::units the index's units, box, tile boxes and z_top alone (no sources, no bounds:
// what a render whose tiles are all read from their files needs), the rest checked for its sizes;
// with SourcePart::grid the grid's arrays and the directions with the units alone (what a render
// holding the index builds stems from); with SourcePart::sources the units and the stems' sources
// (index.parts.sources; no bounds: what building stems needs besides the units' own blocks).
// `blocks` (when given): where each unit's stems lie in `data`, in index.units' order.
// With `net` (the grid a render builds stems on) the x, y of a geographic DEM the source refers to
// are made where read, by blocks (DrainageGrid::node_blocks: GeographicNodeXY), and its heights
// read by blocks through `heights` where given (a render's terrain cache; the DEM opened for its
// georeference alone), else read whole; each block checked by its hashes as it is made, throwing
// penink::Error(internal) where one differs.
// `net` (when given, with the grid's arrays): where the source stores the network, its mains, and
// its in-degrees (inflow_counts' values), orders and flows filled by blocks (FlowNetwork::blocks: each block
// decoded from these bytes the first time a walk reaches it; the bytes must outlive net), and no
// accumulation, basins or outlets; else network_of_directions of the decoded grid and
// directions, made beside the DEM's heights read again where the source refers to its DEM (on
// /tmp/j10.tif 0.5 s of network beside 0.7 s of reading); it may throw as that does.
enum class SourcePart { units, index, grid, all, sources };
struct SourceUnitBlock {
    std::uint64_t at = 0;               // offset of its coded ids in the source's bytes
    std::uint32_t count = 0;            // its stems
    std::uint32_t ids = 0, bounds = 0;  // coded bytes of its ids, then of their bounds
};
// Only the pages of what is decoded are read from a file (the units alone: the head and the units'
// table).
bool decode_crease_source(const CreaseSourceBytes& src, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index, SourcePart part = SourcePart::all,
                          std::vector<SourceUnitBlock>* blocks = nullptr, FlowNetwork* net = nullptr,
                          const NodeHeights* heights = nullptr);
bool decode_crease_source(const std::uint8_t* data, std::size_t size, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index, SourcePart part = SourcePart::all,
                          std::vector<SourceUnitBlock>* blocks = nullptr);
// A unit's stems from its block: their ids (ascending) and bounds; false when they do not decode
// (the block must lie in the source; its pages alone are read).
bool decode_crease_unit(const CreaseSourceBytes& src, const SourceUnitBlock& block, std::vector<std::uint32_t>& ids,
                        std::vector<StemBound>& bounds);

// The accumulation, orders, in-degrees, basins and outlets of the flow directions `dir` on g's
// valid nodes (accumulate_flow and label_basins, one beside the other).
FlowNetwork network_of_directions(const DrainageGrid& g, const std::vector<std::uint8_t>& dir);

}  // namespace penink
