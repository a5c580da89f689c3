// The hachures of a frame (scene/hachure_lines.hpp) on a DEM whose nodes are finer than the
// image's pixels: they work from every hachure_node_step-th node, so a whole view of a fine DEM
// read from its terrain cache reads a share of the nodes that follows the image, not the DEM;
// nodes read beforehand (hachure_nodes) draw the same hachures.
#include <cstdio>
#include <optional>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/checked_blocks.hpp"
#include "scene/hachure_lines.hpp"
#include "surface/terrain_cache.hpp"
#include "support/synthetic_terrain.hpp"
#include "support/temp_dir.hpp"

namespace penink {
namespace {

TerrainCacheKey key() { return {1, 2, 3, 0, true}; }

// Straight down (orthographic) on the whole DEM, or in perspective from the south-west, at
// width x height pixels.
Camera whole_view(const StoredTerrain& t, int width, int height, bool perspective = false) {
    std::vector<glm::dvec3> corners;
    for (const int c : {0, t.nodes.cols - 1})
        for (const int r : {0, t.nodes.rows - 1}) {
            const glm::vec3 p = t.nodes.at(c, r);
            corners.emplace_back(p.x, p.y, double(t.lod.z_min));
            corners.emplace_back(p.x, p.y, double(t.lod.z_max));
        }
    if (perspective) return frame_points(corners, {.azimuth = 225.0, .altitude = -40.0, .width = width, .height = height, .view_width = 0.0, .fill = 1.0});
    return frame_points_orthographic(corners, {.azimuth = 0.0, .altitude = -89.0, .width = width, .height = height,
                                               .view_width = 0.0, .fill = 1.0});
}

GridWindow whole(const GridNodes& n) { return {0, 0, n.cols, n.rows}; }

// The terrain cache of a 2049^2 DEM (a smooth hill 400 m high, sigma 1200 m, on a 5120 m square)
// written in `dir`; its path.
std::string fine_dem_cache(const test::TempDir& dir) {
    const StoredTerrain mem = store_terrain(terrain_from_function(2049, 2049, 2.5, gaussian_hill(400.0, 1200.0)));
    const std::string path = dir.file("fine.lod");
    write_terrain_cache(path, mem, key());
    return path;
}

// All of a terrain read from a cache, modelled at exaggeration 1.
FrameTerrain whole_frame(const StoredTerrain& map) {
    FrameTerrain terrain;
    terrain.meta = map.meta, terrain.nodes = map.drawn(1.0), terrain.lod = map.lod, terrain.storage = map.storage;
    terrain.window = whole(terrain.nodes);
    return terrain;
}

// A 1025^2 DEM of 5 m cells (5120 m a side) framed in 75 rows of pixels: a cell spans about
// 75 / 1025 = 0.073 px, so every 8th node keeps cells within a pixel (0.59 px) and every 16th
// would not (1.17 px); at 150 rows every 4th (0.59 px; every 8th: 1.17 px); at 750 rows a cell
// spans 0.73 px and every node is used.
TEST(HachureLines, NodeStepFollowsThePixelsACellSpans) {
    const StoredTerrain t = store_terrain(terrain_from_function(1025, 1025, 5.0, rough_hills));
    const GridNodes n = t.drawn(1.0);
    EXPECT_EQ(hachure_node_step(n, whole(n), whole_view(t, 100, 75)), 8);
    EXPECT_EQ(hachure_node_step(n, whole(n), whole_view(t, 200, 150)), 4);
    EXPECT_EQ(hachure_node_step(n, whole(n), whole_view(t, 1000, 750)), 1);
    EXPECT_EQ(hachure_node_step(n, GridWindow{0, 0, 1, 1}, whole_view(t, 100, 75)), 1) << "no cell: every node";
}

TEST(HachureLines, SampledNodesAreEveryStepthNode) {
    const StoredTerrain t = store_terrain(terrain_from_function(11, 9, 5.0, rough_hills));
    const GridNodes n = t.drawn(1.0);
    const SampledWindow s = sampled_window(n, GridWindow{1, 2, 11, 9}, 4);  // columns 1, 5, 9; rows 2, 6
    ASSERT_EQ(s.cols, 3);
    ASSERT_EQ(s.rows, 2);
    std::vector<glm::vec3> pos(6);
    std::vector<std::uint8_t> valid(6);
    read_sampled(n, s, GridWindow{0, 0, 3, 2}, pos.data(), valid.data());
    for (int j = 0; j < s.rows; ++j)
        for (int i = 0; i < s.cols; ++i) {
            const std::size_t from = n.index(1 + 4 * i, 2 + 4 * j), to = std::size_t(j) * s.cols + i;
            EXPECT_EQ(pos[to], n.pos[from]);
            EXPECT_EQ(valid[to], n.valid[from]);
        }
    // a part alone: sampled columns 1..2 of row 1, nodes (5, 6) and (9, 6)
    read_sampled(n, s, GridWindow{1, 1, 3, 2}, pos.data(), valid.data());
    EXPECT_EQ(pos[0], n.pos[n.index(5, 6)]);
    EXPECT_EQ(pos[1], n.pos[n.index(9, 6)]);
}

// The hachures of a whole view (in perspective from the south-west, 40 deg down) from the terrain
// cache of a 2049^2 DEM (a smooth hill 400 m high, sigma 1200 m, on a 5120 m square): at
// 2000 x 1500 (every node used) the frame reads every block of the nodes; at 200 x 150 (every 8th
// node) it reads the blocks of every 8th row, a tile of 256 sampled nodes at a time (a row of 2049
// nodes spans about 8 blocks of 256 nodes, read in 2 tiles whose edge's blocks both tiles read:
// about 10/64 of them, and the 2 x 2 nodes of the stencil's lattice of 16 x 16), under 0.4 of
// them, and keeps none of them in place (read_sampled: their memory is not held), nor the rows
// between; both draw hachures.
TEST(HachureLines, WholeViewOfAFineDemReadsWhatTheImageNeeds) {
    test::TempDir dir;
    const std::string path = fine_dem_cache(dir);
    const glm::dvec3 light = glm::normalize(glm::dvec3(-1.0, 1.0, 1.0));
    auto hachures = [&](int width, int height, std::uint64_t& bytes_read, std::vector<bool>* rows_read) {
        const std::optional<StoredTerrain> map = read_terrain_cache(path, key());
        if (!map) throw std::runtime_error("not opened");
        const FrameTerrain terrain = whole_frame(*map);
        const Camera cam = whole_view(*map, width, height, true);
        EXPECT_EQ(hachure_node_step(terrain.nodes, terrain.window, cam), width == 200 ? 8 : 1);
        Drawing drawing;
        add_hachures(terrain, cam, DepthImage{}, light, hachure_defaults(), drawing);
        const CheckedBlocks& blocks = *map->nodes.blocks;
        bytes_read = blocks.bytes_read();
        if (rows_read)
            for (int r = 0; r < 8; ++r)  // the middle node of rows 1000..1007
                rows_read->push_back(blocks.has_read(GridNodes::pos_array, map->nodes.index(1024, 1000 + r)));
        return drawing.layer(LayerKind::hachures).strokes.size();
    };
    std::uint64_t full = 0, coarse = 0;
    std::vector<bool> rows;
    EXPECT_GT(hachures(2000, 1500, full, nullptr), 100u);
    EXPECT_GT(hachures(200, 150, coarse, &rows), 10u);
    std::printf("hachures of a 2049^2 cache: %llu bytes read at 2000x1500, %llu at 200x150\n",
                (unsigned long long)full, (unsigned long long)coarse);
    EXPECT_LT(double(coarse), 0.4 * double(full));
    EXPECT_EQ(rows, std::vector<bool>(8, false));
}

// The hachures traced on nodes found beforehand (hachure_nodes, as a frame finds them while its
// drainage lines are prepared) are the hachures add_hachures finds and traces itself, point for
// point, on the fine DEM's cache at every 8th node (200 x 150: read by tiles as the lines reach
// them) and at every node (2000 x 1500, its window then read into place).
TEST(HachureLines, NodesReadBeforehandDrawTheSameHachures) {
    test::TempDir dir;
    const std::string path = fine_dem_cache(dir);
    const glm::dvec3 light = glm::normalize(glm::dvec3(-1.0, 1.0, 1.0));
    for (const auto& [width, height, step] : {std::tuple{200, 150, 8}, std::tuple{2000, 1500, 1}}) {
        SCOPED_TRACE(testing::Message() << width << " x " << height);
        const std::optional<StoredTerrain> map = read_terrain_cache(path, key());
        ASSERT_TRUE(map);
        const FrameTerrain terrain = whole_frame(*map);
        const Camera cam = whole_view(*map, width, height, true);
        const HachureNodes nodes = hachure_nodes(terrain, cam);
        ASSERT_EQ(nodes.sampled.step, step);
        EXPECT_EQ(nodes.sampled.cols, 2048 / step + 1);
        EXPECT_EQ(map->nodes.blocks->has_read(GridNodes::pos_array, map->nodes.index(1024, 1000)), step == 1)
            << "the window read into place at step 1 alone";
        Drawing beforehand, itself;
        NodeTileCounts tiles;
        add_hachures(terrain, nodes, cam, DepthImage{}, light, hachure_defaults(), beforehand, &tiles);
        // at every 8th node 257 x 257 sampled nodes (0.86 MB) in 2 x 5 tiles of 256 x 64, all held
        // at once: each read once
        EXPECT_EQ(tiles.distinct, step == 1 ? 0u : 10u);
        EXPECT_EQ(tiles.reads, tiles.distinct);
        if (step > 1) {
            EXPECT_EQ(hachure_tiles_line(nodes.sampled, tiles),
                      "hachures: every 8 nodes (257 x 257 sampled), 10 reads of 10 tiles of 256 x 64, 2.03 MiB held at most");
        }
        add_hachures(terrain, cam, DepthImage{}, light, hachure_defaults(), itself);
        const std::vector<Stroke>& a = beforehand.layer(LayerKind::hachures).strokes;
        const std::vector<Stroke>& b = itself.layer(LayerKind::hachures).strokes;
        ASSERT_GT(a.size(), 10u);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            ASSERT_EQ(a[i].points, b[i].points) << i;
            ASSERT_EQ(a[i].weight, b[i].weight) << i;
        }
    }
}

}  // namespace
}  // namespace penink
