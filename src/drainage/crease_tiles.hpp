// The creases of a drainage network built where they are needed: the stems grouped in square
// tiles of the drainage grid by their source cell, a tile's stems built together (crease_part,
// draped_lines.hpp: the whole build's lines bit for bit) the first time a query needs them, and
// kept. A query for a plan box needs every tile holding a stem whose reach (stem_reach.hpp: where
// its crease can lie, from its cells) meets the box, so the lines it returns include every line of
// the whole build meeting the box.
// Tile size: 256 x 256 cells. On jacksboro refined to 0.6" (2015 x 1720 cells) one such tile
// builds in about 0.03 s and all of them one after the other about as fast as the whole build
// (bench/line_parts_bench.cpp); 64-cell tiles cost 1.6 times the whole build in all (each brings
// its stems' trunks along), 512-cell ones four times a 256-cell tile for a frame that needs one.
// Made once (the constructor): the stems' sources and box (stem_parts) and each tile's reach,
// from one walk of every stem (its cells, 4 B a vertex while it runs).
// With a tile store, a tile needed is first looked for in its file (line_tile_files.hpp: read
// when its key, sizes and checksum hold and it lists the tile's stems), else built and its file
// written, so the next process reads what this one built.
// Not thread-safe: one query at a time (a tile's build runs on all cores).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/dem_surface.hpp"
#include "drainage/draped_lines.hpp"

namespace penink {

// Where built tiles are kept between processes: one file a tile in `folder` (none: empty), each
// keyed by hash64 of `key` (the caller's: what the network was built from), the tile size and
// the tile's index.
struct TileStore {
    std::string folder;
    std::uint64_t key = 0;
};

// What a CreaseTiles is made from besides the network: the tile side (cells), the stems' sources
// and box (stem_parts), and each tile's plan box of its stems' reaches (row-major tiles; empty,
// hi < lo, for a tile without stems). Made by one walk of every stem (crease_tile_index); a
// database stores it (crease_source.hpp) so that a render makes its tiles without that walk.
struct CreaseTileIndex {
    int side = 256;
    StemParts parts;
    std::vector<glm::vec2> lo, hi;
};
CreaseTileIndex crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                                  int tile = 256);

class CreaseTiles {
public:
    // g, dir and net must outlive this (g.z: the original elevations, as build_draped_lines reads);
    // with before_first_build, only g's cols and rows are read before the first build.
    // On a DEM without relief (has_relief) the whole build keeps no creases: make none there.
    CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net, int tile = 256,
                TileStore store = {});
    // The same from a stored index (crease_tile_index of this network; index.side is the tile size).
    CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                CreaseTileIndex index, TileStore store = {});

    // The stems whose tiles' reach meets the closed plan box [lo, hi], built where not yet, in
    // stem order (network_stems' ids in `ids`), indexed: lines_meeting_box on it gives the whole
    // build's lines meeting the box, in the same order, equal bit for bit.
    DrapedLineSet lines_for_box(glm::vec2 lo, glm::vec2 hi, std::vector<std::uint32_t>* ids = nullptr);
    // The same lines without copying their vertices: each line's record (box, length, count,
    // order; `first` meaningless) and a pointer to its vertices in its tile, which stays valid
    // and unchanged as long as this object lives.
    struct LineRefs {
        std::vector<DrapedLine> lines;
        std::vector<const DrapedVertex*> vertices;
    };
    LineRefs line_refs_for_box(glm::vec2 lo, glm::vec2 hi);

    // Called once, before the first tile is built here (not for tiles read from their files): a
    // caller that made g, dir and net with their sizes only fills them there.
    void before_first_build(std::function<void()> f) { before_build_ = std::move(f); }

    std::size_t tile_count() const { return tiles_.size(); }
    // The index the tiles were made from (crease_tile_index's, or the one given).
    CreaseTileIndex index() const;
    std::size_t tiles_built() const;  // in memory: built here or read
    std::size_t tiles_read() const { return read_; }        // from their files
    std::size_t tiles_written() const { return written_; }  // files written

private:
    struct Pick {
        std::uint32_t stem;
        const DrapedLineSet* set;
        std::uint32_t line;
    };
    std::vector<Pick> picks_for_box(glm::vec2 lo, glm::vec2 hi);  // built where needed, in stem order
    struct Tile {
        std::vector<std::uint32_t> stems;  // ids, ascending
        glm::vec2 lo{0.0f}, hi{-1.0f};     // plan box of its stems' reaches
        std::unique_ptr<DrapedLineSet> lines;  // built: line i is stems[i]
    };
    const DrainageGrid& g_;
    const std::vector<std::uint8_t>& dir_;
    const FlowNetwork& net_;
    int side_ = 256;
    TileStore store_;
    std::size_t read_ = 0, written_ = 0;
    StemParts parts_;
    std::vector<Tile> tiles_;
    std::unique_ptr<DemSurface> surface_;  // made with the first tile built
    std::function<void()> before_build_;
};

}  // namespace penink
