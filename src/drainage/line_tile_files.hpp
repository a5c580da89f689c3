// Built tiles of creases kept on disk between processes (crease_tiles.hpp): one file a tile in a
// folder beside the drainage database, written whole to a temporary file and renamed (a reader
// sees the old file, the new one or none, never part of one), and read only when a query needs
// the tile. A file holds its key (what the tile was built from: the caller's hash of the
// database's identity, the tile size and the tile's index), the tile's stem ids, each line's
// vertex count and order, the vertices (28 B each, as line_set.hpp lays them out), and a hash64
// of all that; a file of another key, cut short or with a wrong checksum reads as absent, and the
// tile is built again and its file rewritten.
// Layout (little-endian): u32 magic "PNLT", u32 version, u64 key, u32 stems, u32 lines,
// u64 vertices, stems x u32, lines x (u32 count, u8 order), vertices x 28 B, u64 hash64 of every
// byte before it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "drainage/line_set.hpp"

namespace penink {

// The file of tile `tile` in `folder`.
std::string line_tile_path(const std::string& folder, std::uint32_t tile);

// Writes the tile (its stems' ids and lines) atomically (creating the folder); false when it
// cannot be written (a read-only folder, a full disk): the tile then stays in memory only.
bool write_line_tile(const std::string& path, std::uint64_t key, const std::vector<std::uint32_t>& stems,
                     const DrapedLineSet& lines);

// Reads the tile written with `key`: true with its stems and lines (indexed: index_lines), false
// when the file is absent, of another key or version, or damaged (short, checksum, sizes).
bool read_line_tile(const std::string& path, std::uint64_t key, std::vector<std::uint32_t>& stems,
                    DrapedLineSet& lines);

}  // namespace penink
