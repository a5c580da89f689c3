// Built tiles of creases kept on disk between processes (crease_tiles.hpp): one file a tile's
// level in a folder beside the drainage database, written whole to a temporary file and renamed
// (core/cache_file_write.hpp: a reader sees the old file, the new one or none, never part of
// one), and read only when a query needs a stem of the tile that is not kept in memory. A file
// holds every stem of its tile and level (crease_tiles.hpp), in stem order: its key (what the tile
// was built from: the caller's hash of the database's identity, the tile size and the tile's
// index), each line's vertex count and Strahler order, the stems' ids (the first, then each
// one's step from the one before, as u32 bytes, deflated) and bounds (stem_reach.hpp
// encode_stem_bounds), so that a query tests them without the database's index, the vertices
// coded losslessly (core/block_codec.hpp encode_float_planes: the seven floats of each vertex, x,
// y, z, the normal and the flow, each differenced once along the tile's vertices, zigzagged, in
// byte planes, each plane deflated or, where that saves under a tenth, kept as it is, so reading
// inflates only the planes worth it; the normal's z stored as the step of its bits from the one
// its x and y give, nearly always 0; on /tmp/j29.tif's long stems 28 B a vertex as stored in
// memory code to about 13), and a hash64 of all that. The lines' boxes, lengths and index are
// made again when read (index_lines), as the build makes them. A file of another key or version,
// cut short, with a wrong checksum, ids not ascending or that does not decode reads as absent:
// the tile is built again and its file rewritten.
// Layout (little-endian): u32 magic "PNLT", u32 version, u64 key, u32 lines, u64 vertices,
// lines x (u32 count, u8 order), u64 coded size, the coded ids, u64 coded size, the coded bounds,
// u64 coded size, the coded vertices, u64 hash64 of every byte before it.
#pragma once
#include <cstdint>
#include <string>

#include "drainage/line_lattice.hpp"
#include "drainage/line_set.hpp"
#include "drainage/stem_reach.hpp"

namespace penink {

// The file of level `level` of tile `tile` in `folder` (tile-K-L.pnlt), or of its copy at detail
// d > 0 (tile-K-L-dD.pnlt: crease_tiles.hpp).
std::string line_tile_path(const std::string& folder, std::uint32_t tile, int level, int detail = 0);

// A tile file's content: its lines (every one with at least one vertex) and, for line i, its stem
// id stems[i] (ascending) and bound bounds[i].
struct TileLines {
    DrapedLineSet lines;
    std::vector<std::uint32_t> stems;
    std::vector<StemBound> bounds;
};

// The bytes of a tile file holding `lines`, of stems `stems` with bounds `bounds` (one each a line),
// their vertices on `lattice`; none when a vertex is not on it (vertex_code).
std::vector<std::uint8_t> encode_line_tile(std::uint64_t key, const LineLattice& lattice, const DrapedLineSet& lines,
                                           const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds);
// Decodes a tile file's bytes written with `key`: true with its lines (indexed: index_lines),
// false when they are of another key or version, or damaged (short, checksum, sizes, coding).
bool decode_line_tile(const std::uint8_t* data, std::size_t size, std::uint64_t key, TileLines& out);

// Writes the tile atomically (creating the folder); false when it cannot be written (a
// read-only folder, a full disk, a vertex not on the lattice): the tile then stays in memory only.
bool write_line_tile(const std::string& path, std::uint64_t key, const LineLattice& lattice, const DrapedLineSet& lines,
                     const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds);
// Reads the tile written with `key` (decode_line_tile); false also when the file is absent or
// not a regular file.
bool read_line_tile(const std::string& path, std::uint64_t key, TileLines& out);

}  // namespace penink
