// A grid's nodes read on demand in tiles through a bounded cache (lines/node_tiles.hpp): every
// node as in memory wherever the reader walks, the cache's bytes within its budget, tiles read
// again once dropped, and nodes read alone without reading their tiles.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "lines/node_tiles.hpp"

using namespace penink;

namespace {

// A 37 x 23 grid (x = c, y = r, z = c r; every 5th node without data) and a reader of its nodes
// that counts the nodes it gives.
struct Grid {
    int cols = 37, rows = 23;
    std::vector<glm::vec3> pos;
    std::vector<std::uint8_t> valid;
    std::size_t nodes_read = 0;
    Grid() {
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) {
                pos.emplace_back(float(c), float(r), float(c * r));
                valid.push_back((r * cols + c) % 5 != 0);
            }
    }
    NodeReader reader() {
        return [this](GridWindow part, glm::vec3* p, std::uint8_t* v) {
            for (int r = part.r0; r < part.r1; ++r)
                for (int c = part.c0; c < part.c1; ++c) {
                    *p++ = pos[std::size_t(r) * cols + c], *v++ = valid[std::size_t(r) * cols + c];
                    ++nodes_read;
                }
        };
    }
};

}  // namespace

// Tiles of 8 x 4 nodes (5 x 6 of them, the last column and row cut short: 5 and 3 nodes), a
// budget of 3 tiles (3 x 32 x 13 = 1248 B): a walk down every column then along every row gives
// every node as the grid holds it; the cache holds 1248 B at most, and reads the tiles again as
// the walks come back to them.
TEST(NodeTiles, EveryNodeAsInMemoryWithinTheBudget) {
    Grid g;
    const std::size_t budget = 3 * 8 * 4 * NodeTiles::node_bytes;
    NodeTiles tiles(g.cols, g.rows, g.reader(), budget, 8, 4);
    NodeTiles memory(g.cols, g.rows, g.pos.data(), g.valid.data());
    const auto check = [&](int c, int r) {
        const std::size_t i = std::size_t(r) * g.cols + c;
        ASSERT_EQ(tiles.pos(c, r), g.pos[i]) << c << " " << r;
        ASSERT_EQ(tiles.valid(c, r), g.valid[i] != 0) << c << " " << r;
        ASSERT_EQ(memory.pos(c, r), g.pos[i]) << c << " " << r;
        ASSERT_EQ(memory.valid(c, r), g.valid[i] != 0) << c << " " << r;
        ASSERT_LE(tiles.held_bytes(), budget);
    };
    for (int c = 0; c < g.cols; ++c)
        for (int r = 0; r < g.rows; ++r) check(c, r);
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) check(c, r);
    const NodeTileCounts& n = tiles.counts();
    EXPECT_EQ(tiles.held_bytes(), budget);
    EXPECT_EQ(n.most_bytes, budget);
    EXPECT_EQ(n.distinct, 30u);
    // down each column: the 6 tiles of its column of tiles, read again for each of its 8 columns
    // (5 in the last) of nodes, 5 x 6 x 8 - 6 x 3 = 222; along each row: every tile of the row of
    // tiles (5), again for each of its 4 rows of nodes (3 in the last), 23 x 5 = 115
    EXPECT_EQ(n.reads, 222u + 115u);
    EXPECT_EQ(n.probes, 0u);
    EXPECT_EQ(memory.counts().reads, 0u) << "in memory: nothing read";
}

// A node read alone (probe_pos) is its node: with its neighbours east and south (2 x 2 nodes,
// fewer at the grid's edge), its tile not read when not held, its neighbours then taken from
// them; from its tile when held. A tile is read whole, its nodes then all from it.
TEST(NodeTiles, ProbesReadTwoByTwoNodes) {
    Grid g;
    NodeTiles tiles(g.cols, g.rows, g.reader(), 1 << 20, 8, 4);
    const auto at = [&](int c, int r) { return g.pos[std::size_t(r) * g.cols + c]; };
    EXPECT_EQ(tiles.probe_pos(30, 20), at(30, 20));
    EXPECT_EQ(g.nodes_read, 4u);
    EXPECT_EQ(tiles.probe_pos(31, 20), at(31, 20));
    EXPECT_EQ(tiles.probe_pos(30, 21), at(30, 21));
    EXPECT_EQ(g.nodes_read, 4u) << "its neighbours read with it";
    EXPECT_EQ(tiles.probe_pos(36, 22), at(36, 22));
    EXPECT_EQ(g.nodes_read, 5u) << "the grid's last node: alone";
    EXPECT_EQ(tiles.counts().reads, 0u);
    EXPECT_EQ(tiles.counts().probes, 2u);
    EXPECT_EQ(tiles.held_bytes(), 0u);
    EXPECT_EQ(tiles.pos(9, 5), at(9, 5));  // tile (1, 1): 8 x 4 nodes
    EXPECT_EQ(g.nodes_read, 5u + 32u);
    EXPECT_EQ(tiles.probe_pos(15, 7), at(15, 7));  // the same tile
    EXPECT_EQ(g.nodes_read, 37u);
    EXPECT_EQ(tiles.counts().probes, 2u);
    EXPECT_EQ(tiles.counts().reads, 1u);
}

// With 3 tiles held (of tile rows 2, 3 and 0, the last the most recently used), a fourth drops
// the least recently used (tile row 2); once the sweep has reached row 9 (tile row 2) it drops the
// one north of it (tile row 0) instead, and tile row 2 is still held.
TEST(NodeTiles, TilesNorthOfTheSweepAreDroppedFirst) {
    Grid g;
    for (const bool swept : {false, true}) {
        SCOPED_TRACE(swept ? "swept" : "no sweep");
        NodeTiles tiles(g.cols, g.rows, g.reader(), 3 * 8 * 4 * NodeTiles::node_bytes, 8, 4);
        tiles.pos(0, 0), tiles.pos(0, 8), tiles.pos(0, 12), tiles.pos(0, 1);  // tile rows 0, 2, 3, 0
        if (swept) tiles.sweep(9);
        tiles.pos(0, 16);  // tile row 4
        EXPECT_EQ(tiles.counts().reads, 4u);
        EXPECT_EQ(tiles.pos(0, 9), g.pos[std::size_t(9) * g.cols]);
        EXPECT_EQ(tiles.counts().reads, swept ? 4u : 5u) << "tile row 2 held when swept";
    }
}
