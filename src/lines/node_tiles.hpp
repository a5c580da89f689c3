// A grid's nodes (positions and valid flags, cols x rows, row-major, row 0 north) for a reader
// that walks them here and there (the hachures, lines/hachures.hpp): either held in memory whole,
// or read on demand in tiles of tile_cols x tile_rows nodes (the grid's last column and row of
// tiles cut short) through a cache that holds at most `budget` bytes of them (13 B a node: at
// most budget / (tile_cols x tile_rows x 13) tiles, and never fewer than 2), the tile used least
// recently dropped first (a tile is "used" when the reader moves onto it from another tile). A
// reader that sweeps the grid north to south (the hachures' seed lattice) says which row it has
// reached (sweep): the tiles of the rows of tiles north of that row's are dropped first, least
// recently used first among them, as the sweep does not come back to them (on the hachures of
// the views below it reads 13-15 % fewer tiles than least recently used alone). Either
// way a node has the values its source gives: the cache changes where they are kept, not what
// they are. So the memory of a grid read on demand is bounded whatever its size, and its cost is
// the tiles read, again after being dropped where the reader comes back to them (counted in
// NodeTileCounts). A node of a tile not held can also be read with its neighbours alone (probe:
// the 2 x 2 nodes from it east and south, kept until the next such read; its tile not read,
// nothing dropped), for a lattice of a few cells spread over the whole grid.
// Not thread-safe: one reader.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "input/terrain.hpp"

namespace penink {

// Nodes [part.c0, part.c1) x [part.r0, part.r1) of a grid, row-major (part.cols() x part.rows()
// of each), into pos and valid.
using NodeReader = std::function<void(GridWindow part, glm::vec3* pos, std::uint8_t* valid)>;

// What a cache of tiles did: tiles read (reads; distinct: different tiles among them), 2 x 2
// nodes read alone (probes), and the most bytes it held at once.
struct NodeTileCounts {
    std::size_t reads = 0, distinct = 0, probes = 0, most_bytes = 0;
};

class NodeTiles {
public:
    // The tile shape and cache budget of a grid read on demand (the hachures'): tiles of 256 x 64
    // nodes (208 KiB; a tile's row of 256 sampled nodes spans several of the terrain cache's
    // 256-node blocks, the two at its ends shared with the tiles beside it) and 32 MiB (157 tiles).
    // On the whole view of jacksboro refined 29 times (11687 x 9976 nodes, sampled at every 4th:
    // 2922 x 2494, 468 tiles) the hachures read 472 tiles, 296 of 264 and 431 of 390 on two
    // closer views (docs/timings.md; `penink render -v` prints the counts). A larger budget reads
    // fewer again (468, 264, 390 at 64 MiB) but its slots are fresh memory the frame zeroes page
    // by page: 64 MiB made the whole view's hachures 80 ms slower and its peak 33 MB higher; 8 MiB
    // read 1306 tiles for 468.
    static constexpr int default_tile_cols = 256, default_tile_rows = 64;
    static constexpr std::size_t default_budget = std::size_t(32) << 20;
    static constexpr std::size_t node_bytes = sizeof(glm::vec3) + sizeof(std::uint8_t);

    // The nodes in memory (one tile, the whole grid).
    NodeTiles(int cols, int rows, const glm::vec3* pos, const std::uint8_t* valid);
    // The nodes read through `read`, a tile at a time, at most `budget` bytes held (2 tiles at least).
    NodeTiles(int cols, int rows, NodeReader read, std::size_t budget = default_budget,
              int tile_cols = default_tile_cols, int tile_rows = default_tile_rows);

    // Node (c, r) (inside the grid): its position and whether it holds data; its tile read if not held.
    glm::vec3 pos(int c, int r) {
        const std::size_t i = offset(c, r);  // first: it may change the current tile
        return cur_pos_[i];
    }
    bool valid(int c, int r) {
        const std::size_t i = offset(c, r);
        return cur_valid_[i] != 0;
    }
    // The position of node (c, r) from its tile when held, else from the 2 x 2 nodes last read
    // alone when among them, else from nodes (c, r) .. (c + 1, r + 1) (within the grid) read alone.
    glm::vec3 probe_pos(int c, int r);

    // The row the reader's sweep north to south has reached (< 0: no sweep, least recently used alone).
    void sweep(int r) { sweep_ = r < 0 ? -1 : r / tile_rows_; }

    int tile_cols() const { return tile_cols_; }
    int tile_rows() const { return tile_rows_; }
    std::size_t held_bytes() const { return held_bytes_; }
    const NodeTileCounts& counts() const { return counts_; }

private:
    struct Tile {
        int index = -1;            // tile row x tiles_across_ + tile column; -1: empty
        std::uint64_t used = 0;    // when the reader last moved onto it
        GridWindow part;
        std::vector<glm::vec3> pos;
        std::vector<std::uint8_t> valid;
    };

    // The offset of node (c, r) in the current tile, made the one holding it.
    std::size_t offset(int c, int r) {
        if (unsigned(c - cur_.c0) >= unsigned(cur_.cols()) || unsigned(r - cur_.r0) >= unsigned(cur_.rows())) enter(c, r);
        return std::size_t(r - cur_.r0) * std::size_t(cur_.cols()) + std::size_t(c - cur_.c0);
    }
    // Makes the tile of node (c, r) current: held, or read into a free slot or the slot of the
    // tile dropped (dropped_slot).
    void enter(int c, int r);
    // The held tile to drop: the least recently used north of the sweep's row of tiles, else the
    // least recently used.
    int dropped_slot() const;
    int tile_index(int c, int r) const { return (r / tile_rows_) * tiles_across_ + c / tile_cols_; }
    GridWindow tile_part(int index) const;

    int cols_ = 0, rows_ = 0;
    int tile_cols_ = 0, tile_rows_ = 0, tiles_across_ = 1;
    NodeReader read_;
    std::size_t max_slots_ = 0;       // budget / tile bytes, 2 at least
    std::vector<Tile> slots_;
    std::vector<int> slot_of_;        // per tile: its slot, or -1 when not held
    std::vector<std::uint8_t> seen_;  // per tile: read before
    std::uint64_t clock_ = 0;
    int sweep_ = -1;                  // the sweep's row of tiles; -1: none
    std::size_t held_bytes_ = 0;
    NodeTileCounts counts_;
    GridWindow probe_;                // the nodes last read alone (empty: none)
    glm::vec3 probe_pos_[4];
    std::uint8_t probe_valid_[4];
    GridWindow cur_;                  // the current tile's nodes (empty: none)
    const glm::vec3* cur_pos_ = nullptr;
    const std::uint8_t* cur_valid_ = nullptr;
};

}  // namespace penink
