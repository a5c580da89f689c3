// The nodes a whole view is framed by (frame_samples, scene/terrain_view.hpp): every k-th node of
// every k-th row (all of them on a small grid) and every edge node, as drawn (exaggerated, raised
// to the sea), in one order; read from a terrain cache they are the same points in the same order,
// and no block of the cache is kept (a large DEM's frame touches a node or two in most blocks).
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/checked_blocks.hpp"
#include "scene/terrain_view.hpp"
#include "support/synthetic_terrain.hpp"
#include "support/temp_dir.hpp"
#include "surface/terrain_cache.hpp"

namespace penink {
namespace {

TerrainCacheKey key() { return {1, 2, 3, 0, true}; }

// The points frame_samples must give: the loops it is written as, node by node.
std::vector<glm::dvec3> expected_samples(const GridNodes& t) {
    std::vector<glm::dvec3> pts;
    if (t.size() <= 20000) {
        for (std::size_t i = 0; i < t.size(); ++i)
            if (t.has_data(i)) pts.emplace_back(t.at(i));
    } else {
        const int k = int(std::ceil(std::sqrt(double(t.size()) / 20000.0)));
        for (int r = 0; r < t.rows; r += k)
            for (int c = 0; c < t.cols; c += k)
                if (t.has_data(t.index(c, r))) pts.emplace_back(t.at(c, r));
    }
    for (int c = 0; c < t.cols; ++c)
        for (int r : {0, t.rows - 1})
            if (t.has_data(t.index(c, r))) pts.emplace_back(t.at(c, r));
    for (int r = 0; r < t.rows; ++r)
        for (int c : {0, t.cols - 1})
            if (t.has_data(t.index(c, r))) pts.emplace_back(t.at(c, r));
    return pts;
}

}  // namespace

TEST(FrameSamples, CachedNodesGiveTheSamePointsAndKeepNoBlock) {
    test::TempDir dir;
    // 10 k nodes: all of them; 361 k: every 5th of every 5th row; on an affine grid the cache keeps
    // the edge columns, read there (a block every 128 rows of each instead of one a row)
    for (const int side : {101, 601, -601}) {
        Terrain t = terrain_from_function(std::abs(side), std::abs(side) - 20, 5.0, rough_hills);
        t.valid[std::size_t(3 * std::abs(side) + 7)] = 0, t.valid[std::size_t(std::abs(side) - 1)] = 0;  // nodata inside and on an edge
        t.valid[t.index(0, 17)] = 0;  // on the west edge
        if (side < 0) t = on_affine_grid(std::move(t));
        const StoredTerrain mem = store_terrain(t);
        const std::string path = dir.file("t" + std::to_string(side) + ".lod");
        write_terrain_cache(path, mem, key());
        const std::optional<StoredTerrain> map = read_terrain_cache(path, key());
        ASSERT_TRUE(map);
        const double sea = 0.5 * (double(mem.lod.z_min) + double(mem.lod.z_max));  // half the DEM under water
        const GridNodes from_file = map->drawn(2.0, sea), in_memory = mem.drawn(2.0, sea);
        const std::vector<glm::dvec3> want = expected_samples(in_memory), got = frame_samples(from_file);
        ASSERT_EQ(got.size(), want.size()) << side;
        for (std::size_t i = 0; i < want.size(); ++i) ASSERT_EQ(got[i], want[i]) << side << " point " << i;
        EXPECT_EQ(map->nodes.edges_kept, side < 0);
        EXPECT_GT(map->nodes.blocks->blocks_read(), 0u);
        if (side < 0) {  // the same points from the nodes' rows: two blocks more a row (1162 here)
            std::optional<StoredTerrain> rows = read_terrain_cache(path, key());
            ASSERT_TRUE(rows);
            rows->nodes.edges_kept = false;
            EXPECT_EQ(frame_samples(rows->drawn(2.0, sea)), got);
            EXPECT_GT(rows->nodes.blocks->blocks_read(), map->nodes.blocks->blocks_read() + 1100);
        }
        for (std::size_t i = 0; i < from_file.size(); i += 256)
            ASSERT_FALSE(map->nodes.blocks->has_read(GridNodes::pos_array, i)) << side << " node " << i;
    }
}

}  // namespace penink
