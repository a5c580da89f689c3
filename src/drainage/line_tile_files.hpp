// Built tiles of creases kept on disk between processes (crease_tiles.hpp): one file a tile's
// level in a folder beside the drainage database, written whole to a temporary file and renamed
// (core/cache_file_write.hpp: a reader sees the old file, the new one or none, never part of
// one), and read only when a query needs a stem of the tile that is not kept in memory. A file
// holds every stem of its tile and level, or some of them (crease_tiles.hpp crease_partial_share),
// in stem order: its key (what the tile
// was built from: the caller's hash of the database's identity, the tile size and the tile's
// index), the lattice its vertices lie on (line_lattice.hpp: the build drapes every crease vertex
// on it, so the file codes them without loss), the stems' ids (the first, then each one's step
// from the one before, as u32 bytes, deflated) and their lines' bounds (crease_tiles.hpp
// crease_line_bound; coded by stem_reach.hpp encode_stem_bounds), so
// that a query tests them without the database's index, the lines and their vertices, and a
// hash64 of all that. The lines and vertices are coded as integers: each vertex's six lattice
// codes (x, y, z, the normal's two, the flow: vertex_code) less their prediction (along its line,
// x, y and z from the two vertices before it, the step repeated, the others from the one before;
// a line's first vertex from the first of the line before), zigzagged, in byte planes (a row a
// line: its vertex count, Strahler order and first vertex's residuals; then a row for each other
// vertex), deflated (core/block_codec.hpp encode_bytes). On /tmp/j5.tif's whole view at
// 1000x750 (323 files, 231 743 stems, 3.12 M vertices) that is 4.2 B a vertex for the lines and
// vertices and 4.9 B with the ids and bounds (version 5, which kept the floats as they were: 15.3;
// the 28 B a vertex takes in memory); the caches beside the DEM then take 1.93 times its float32
// size (26.7 MB: .dv 6.2, .lod 5.3, tiles 15.2; version 5: 59.2 MB, 4.3 times), on
// /tmp/j29.tif's 1.12 times (522 MB: .dv 194, .lod 114, tiles 214; version 5: 977 MB, 2.1 times);
// `penink render DEM --width 1000 --height 750 -o x.svg`, then `du -cb DEM.dv DEM.lod
// DEM.dv.tiles`. The lines' boxes, lengths and index are made again when read (index_lines), as
// the build makes them. A file of another key or version, cut short, with a wrong checksum, ids
// not ascending or that does not decode reads as absent: the tile is built again and its file
// rewritten.
// Layout (little-endian): u32 magic "PNLT", u32 version, u64 key, i32 plan and z exponents of
// the lattice, u32 lines, u64 vertices, u32 stems left out (TileRest), u64 coded size, the coded
// ids, u64 coded size, the coded bounds, u64 coded size, the coded lines and vertices, where stems
// are left out u64 coded size, their coded ids, u64 coded size, their coded bounds, then u64
// hash64 of every byte before it.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "drainage/line_lattice.hpp"
#include "drainage/line_set.hpp"
#include "drainage/stem_reach.hpp"

namespace penink {

// The file of level `level` of tile `tile` in `folder` (tile-K-L.pnlt), or of its copy at detail
// d > 0 (tile-K-L-dD.pnlt: crease_tiles.hpp).
std::string line_tile_path(const std::string& folder, std::uint32_t tile, int level, int detail = 0);

// The stems of a tile's level that a file of some of them leaves out (crease_tiles.hpp
// crease_partial_share): their ids (ascending) and index bounds, so that a query tells from the
// file alone whether it needs any of them (none: a file of every stem of its level).
struct TileRest {
    std::vector<std::uint32_t> stems;
    std::vector<StemBound> bounds;
    bool operator==(const TileRest&) const = default;
};
// A tile file's content: its lines (every one with at least one vertex) and, for line i, its stem
// id stems[i] (ascending) and bound bounds[i]; and what bounds the stems it leaves out.
struct TileLines {
    DrapedLineSet lines;
    std::vector<std::uint32_t> stems;
    std::vector<StemBound> bounds;
    TileRest rest;
};

// Whether a tile file's lines are needed, from its stems and bounds (decoded first: `lines` still
// empty); where not, the lines are not decoded (a query whose test passes none of its stems).
using TileNeed = std::function<bool(const TileLines&)>;

// The bytes of a tile file holding `lines`, of stems `stems` with bounds `bounds` (one each a line),
// their vertices on `lattice`; none when a vertex is not on it (vertex_code).
std::vector<std::uint8_t> encode_line_tile(std::uint64_t key, const LineLattice& lattice, const DrapedLineSet& lines,
                                           const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds,
                                           const TileRest& rest = {});
// Decodes a tile file's bytes written with `key`: true with its lines (indexed: index_lines),
// false when they are of another key or version, or damaged (short, checksum, sizes, coding).
// With `need`: its stems and bounds alone (lines empty) where need says no line is needed.
bool decode_line_tile(const std::uint8_t* data, std::size_t size, std::uint64_t key, TileLines& out,
                      const TileNeed& need = {});

// Writes the tile atomically (creating the folder); false when it cannot be written (a
// read-only folder, a full disk, a vertex not on the lattice): the tile then stays in memory only.
bool write_line_tile(const std::string& path, std::uint64_t key, const LineLattice& lattice, const DrapedLineSet& lines,
                     const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds,
                     const TileRest& rest = {});
// Reads the tile written with `key` (decode_line_tile); false also when the file is absent or
// not a regular file.
bool read_line_tile(const std::string& path, std::uint64_t key, TileLines& out, const TileNeed& need = {});

}  // namespace penink
