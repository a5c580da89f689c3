// The creases of a drainage database that stores what building them reads (DrainageDb::
// crease_source, crease_source.hpp) instead of the creases: the tile index decoded on the first
// query, the grid and directions when a tile is first built here (the accumulation, orders and
// basins then made again from the directions), the creases built per tile of the drainage grid where a query's plan box needs them
// (crease_tiles.hpp: the whole build's lines bit for bit), each tile kept for the next query and,
// given a folder, in a file of its own (line_tile_files.hpp), so the next process reads it
// instead of building it. A folder that cannot be written keeps the tiles in memory only.
// Tile files are keyed by the database's version and a hash of the stored source bytes: a file
// of another network or builder is built again and rewritten.
// Thread-safe: queries from several threads (frames prepared on threads) run one at a time (a
// tile's build runs on all cores).
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/crease_tiles.hpp"
#include "drainage/line_set.hpp"

namespace penink {

class StoredCreases {
public:
    // `source`: DrainageDb::crease_source (not empty); `folder`: where tile files are kept (none:
    // empty).
    StoredCreases(std::vector<std::uint8_t> source, std::string folder = {});
    ~StoredCreases();

    // The creases meeting the closed plan box [lo, hi] and maybe more, in the stored order,
    // indexed: lines_meeting_box on it gives exactly the lines a database holding every crease
    // gives for the box. Throws penink::Error("drainage", "", ..., internal) when the source does
    // not decode (it was checked by the database's checksum: a builder's fault).
    DrapedLineSet lines_for_box(glm::vec2 lo, glm::vec2 hi);
    // The same lines as records and pointers to their vertices in the kept tiles (valid while this
    // object lives): what a frame selects from without copying the vertices.
    CreaseTiles::LineRefs line_refs_for_box(glm::vec2 lo, glm::vec2 hi);

    // Tiles in all, built here, read from their files (0 before the first query).
    std::size_t tile_count() const;
    std::size_t tiles_built() const;
    std::size_t tiles_read() const;

private:
    struct Decoded;
    mutable std::mutex mutex_;
    std::vector<std::uint8_t> source_;
    std::string folder_;
    std::unique_ptr<Decoded> decoded_;
    CreaseTiles& tiles();  // decoded on first use; under mutex_
};

// The folder beside a drainage database file that keeps its crease tiles.
std::string crease_tile_folder(const std::string& dv_path);

}  // namespace penink
