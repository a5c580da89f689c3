// A render draws the creases `penink drainage` stores the source of (crease_source.hpp) from the
// stems its frame can draw: a frame builds only the stems whose bound (their reach's box and a
// bound of their length) meets its box and passes its screen-size culling, fewer than all, and
// selects the same lines, bit for bit, as a database holding every crease; a later frame of the
// same source builds only the stems it needs that no frame built before (a wider view: the
// difference; the first view again: none); without culling every stem of the whole DEM is built,
// once, and equals the whole build; several frames asking at once (frames prepared on threads)
// get what one asking alone gets. The levels of the tiles a frame needs are kept beside the
// cache (`<dv>.tiles/`, one file each): a later process reads them and builds none; a cache written
// anew removes them. Everything is written in a temporary folder.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/memory_budget.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/line_selection.hpp"
#include "drainage/stored_creases.hpp"
#include "input/dem_reader.hpp"
#include "scene/drainage_lines.hpp"
#include "scene/scene.hpp"
#include "scene/scene_memory.hpp"
#include "scene/terrain_view.hpp"
#include "scene/terrain_frames.hpp"
#include "support/temp_dir.hpp"
#include "surface/terrain_cache.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

bool same_lines(const ScoredLineSet& a, const ScoredLineSet& b) {
    return a.positions.size() == b.positions.size() && a.runs.size() == b.runs.size() &&
           std::memcmp(a.positions.data(), b.positions.data(), sizeof(a.positions[0]) * a.positions.size()) == 0 &&
           std::memcmp(a.normals.data(), b.normals.data(), sizeof(a.normals[0]) * a.normals.size()) == 0 &&
           a.flow == b.flow;
}

// examples/<name> copied into `dir`: its path there.
fs::path example_copy(const fs::path& dir, const std::string& name) {
    const fs::path to = dir / name;
    fs::copy_file(fs::path(PENINK_SOURCE_DIR "/examples") / name, to);
    return to;
}

struct VolcanoCache {
    test::TempDir dir{"stored_creases"};
    Scene scene;
    Terrain t;
    VolcanoCache() {
        const fs::path dem = example_copy(dir.path, "volcano.asc");
        example_copy(dir.path, "volcano.prj");
        scene.source.dem = dem.string();
        scene.view.camera.width = 400, scene.view.camera.height = 300;
        t = read_dem(dem.string());
    }
    // a render's source: the cache read (built the first time), its creases' source undecoded
    DrainageLineSource source() const {
        std::optional<DrainageLineSource> s = scene_drainage(scene, t, Log{});
        EXPECT_TRUE(s && s->creases);
        return std::move(*s);
    }
};

TEST(StoredCreasesRender, AFrameBuildsOnlyTheStemsItCanDrawOnce) {
    const VolcanoCache v;
    DrainageLineSource first = v.source();  // builds and writes the cache
    const DrainageDb whole = build_drainage_db(v.t, DrainageOptions{});
    ASSERT_TRUE(whole.crease_source.empty());
    LineBox all = line_box(v.t), view = all;
    const glm::vec2 size = all.hi - all.lo;  // a tenth of the side, near a corner
    view.lo = all.lo + 0.1f * size, view.hi = all.lo + 0.2f * size;
    const LineCulling culling{{scene_camera(v.scene, v.t)}, line_culling_px(v.scene)};
    ASSERT_GT(culling.min_px, 2.0f);

    // the view: some stems, the lines of a database holding every crease
    DrainageLineSource warm = v.source();
    const DrainageLineData a = prepare_drainage_lines(warm, view, culling);
    const StoredCreases& built = *warm.creases;
    const std::size_t for_view = built.stems_built();
    ASSERT_GT(a.creases.positions.size(), 100u);
    EXPECT_GT(for_view, 0u);
    EXPECT_LT(for_view, built.stem_count() / 4);
    EXPECT_EQ(built.builds(), 1u);
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, view, culling).creases, a.creases));
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, view, culling).ridges, a.ridges));
    // the tiles the view needed written beside the cache; another process reads them, builds none
    const std::string folder = crease_tile_folder(drainage_cache_path(v.scene.source.dem, ""));
    const std::size_t written = built.tiles_written();
    EXPECT_GT(written, 0u);
    EXPECT_EQ(built.tiles_read(), 0u);
    EXPECT_EQ(std::size_t(std::distance(fs::directory_iterator(folder), fs::directory_iterator())), written);
    {
        DrainageLineSource again = v.source();
        EXPECT_TRUE(same_lines(prepare_drainage_lines(again, view, culling).creases, a.creases));
        EXPECT_EQ(again.creases->tiles_read(), written);
        EXPECT_EQ(again.creases->tiles_written(), 0u);
        EXPECT_EQ(again.creases->stems_built(), for_view);
    }

    // the whole DEM: the view's tiles read, the others built and written
    DrainageLineSource alone = v.source();
    const DrainageLineData w = prepare_drainage_lines(alone, all, culling);
    const std::size_t for_all = alone.creases->stems_built();
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, all, culling).creases, w.creases));
    EXPECT_GT(for_all, for_view);
    EXPECT_LT(for_all, built.stem_count());  // the culling leaves stems unbuilt
    EXPECT_GT(alone.creases->tiles_read(), 0u);
    EXPECT_GT(alone.creases->tiles_written(), 0u);
    // the first source again, for the whole DEM, then the view: read, nothing written
    EXPECT_TRUE(same_lines(prepare_drainage_lines(warm, all, culling).creases, w.creases));
    EXPECT_TRUE(same_lines(prepare_drainage_lines(warm, view, culling).creases, a.creases));
    EXPECT_EQ(built.tiles_written(), written);
    // without culling: every stem, the whole build
    const DrainageLineData u = prepare_drainage_lines(warm, all);
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, all).creases, u.creases));
    RecordProperty("stems", int(built.stem_count()));
    RecordProperty("stems_for_view", int(for_view));
    RecordProperty("stems_for_all", int(for_all));
    RecordProperty("vertices_for_all", int(alone.creases->vertices_built()));

    // frames on threads share one source: each gets what it gets alone
    const DrainageLineSource shared = v.source();
    std::vector<DrainageLineData> got(4);
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < got.size(); ++k)
        threads.emplace_back([&, k] { got[k] = prepare_drainage_lines(shared, k % 2 ? all : view, culling); });
    for (std::thread& th : threads) th.join();
    for (std::size_t k = 0; k < got.size(); ++k) EXPECT_TRUE(same_lines(got[k].creases, (k % 2 ? w : a).creases)) << k;

    // a database written anew: its tiles removed (a file not a tile's is left, and the folder)
    std::ofstream(folder + "/note.txt") << "kept";
    remove_crease_tiles(drainage_cache_path(v.scene.source.dem, ""));
    ASSERT_TRUE(fs::exists(folder + "/note.txt"));
    EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1);
    fs::remove(folder + "/note.txt");
    remove_crease_tiles(drainage_cache_path(v.scene.source.dem, ""));
    EXPECT_FALSE(fs::exists(folder));
}

// Without a folder for tiles (a cache that cannot be written), the stems built are kept for the
// next frame of the process: a wider view builds only the difference, the first view again none.
TEST(StoredCreasesRender, WithoutTileFilesTheStemsBuiltAreKept) {
    const VolcanoCache v;
    DvLineVertices in_file;
    DrainageDb db = load_or_build_drainage(v.scene.source.dem, v.t, DrainageOptions{}, {}, {}, &in_file);
    ASSERT_FALSE(db.crease_source.empty());
    const DrainageDb whole = build_drainage_db(v.t, DrainageOptions{});
    LineBox all = line_box(v.t), view = all;
    const glm::vec2 size = all.hi - all.lo;
    view.lo = all.lo + 0.1f * size, view.hi = all.lo + 0.2f * size;
    const LineCulling culling{{scene_camera(v.scene, v.t)}, line_culling_px(v.scene)};
    DrainageLineSource source;
    source.creases = std::make_shared<StoredCreases>(db.crease_source);
    source.db = std::move(db);
    source.db.crease_source.clear();
    const StoredCreases& built = *source.creases;
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, view, culling).creases,
                           prepare_drainage_lines(source, view, culling).creases));
    const std::size_t for_view = built.stems_built();
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, all, culling).creases,
                           prepare_drainage_lines(source, all, culling).creases));
    const std::size_t for_all = built.stems_built();
    EXPECT_GT(for_all, for_view);
    EXPECT_LT(for_all, built.stem_count());
    EXPECT_EQ(built.builds(), 2u);
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, view, culling).creases,
                           prepare_drainage_lines(source, view, culling).creases));
    EXPECT_EQ(built.builds(), 2u);  // nothing built again
    EXPECT_EQ(built.stems_built(), for_all);
    EXPECT_EQ(built.tiles_written(), 0u);
    EXPECT_EQ(built.tiles_read(), 0u);
}

// A source that refers to its DEM (a build at factor 1) builds a frame's stems on the heights its
// walks reach, read by blocks from the terrain cache (terrain_node_heights) instead of the DEM
// read whole: the same lines, bit for bit, from the rows of fewer than all the blocks.
TEST(StoredCreasesRender, HeightsReadByBlocksFromTheTerrainCache) {
    const test::TempDir dir("stored_creases_heights");
    const fs::path dem = example_copy(dir.path, "jacksboro.tif");
    const Terrain t = read_dem(dem.string());
    DrainageOptions o;
    o.resample = 1;
    // a render's source: the cache read (built the first time), its creases' source undecoded
    const auto source = [&] {
        DrainageLineSource s;
        s.db = load_or_build_drainage(dem.string(), t, o, {}, {}, &s.vertices);
        s.creases = StoredCreases::of(s.db);
        return s;
    };
    DrainageLineSource whole = source();
    ASSERT_EQ(crease_source_dem(crease_source_bytes(whole.db)), absolute_dem_path(dem.string()));
    const TerrainCacheKey key{1, 2, 3, 0, true};
    write_terrain_cache(dir.file("j.lod"), store_terrain(read_dem(dem.string())), key);
    const std::optional<StoredTerrain> cached = read_terrain_cache(dir.file("j.lod"), key);
    ASSERT_TRUE(cached && cached->nodes.blocks);
    NodeHeights heights = terrain_node_heights(*cached);
    std::size_t spans = 0;
    heights.span = [&spans, span = heights.span](int r, int c0, int c1, float* z) { ++spans, span(r, c0, c1, z); };

    Scene scene;
    scene.source.dem = dem.string();
    scene.view.camera.width = 400, scene.view.camera.height = 300;
    LineBox all = line_box(t), view = all;
    const glm::vec2 size = all.hi - all.lo;  // a fifth of the side, near a corner
    view.lo = all.lo + 0.1f * size, view.hi = all.lo + 0.3f * size;
    const LineCulling culling{{scene_camera(scene, t)}, line_culling_px(scene)};
    DrainageLineSource by_blocks = source();
    by_blocks.creases->use_node_heights(heights);
    int checks = 0;
    by_blocks.creases->before_first_decode([&checks, &t](int cols, int rows) {
        EXPECT_EQ(cols, t.cols);  // the grid at factor 1
        EXPECT_EQ(rows, t.rows);
        ++checks;
    });
    const DrainageLineData a = prepare_drainage_lines(whole, view, culling);
    const DrainageLineData b = prepare_drainage_lines(by_blocks, view, culling);
    ASSERT_GT(a.creases.positions.size(), 100u);
    EXPECT_TRUE(same_lines(a.creases, b.creases));
    EXPECT_EQ(whole.creases->stems_built(), by_blocks.creases->stems_built());
    // jacksboro's 403 x 344 nodes: 12 blocks of 128 x 128, 4 spans a row for all
    EXPECT_GT(spans, 0u);
    EXPECT_LT(spans, std::size_t(4 * 344));
    ::testing::Test::RecordProperty("height_spans_read", int(spans));
    // the whole DEM: the same again
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, all, culling).creases,
                           prepare_drainage_lines(by_blocks, all, culling).creases));
    EXPECT_EQ(checks, 1);  // before the first build alone

    // a render's memory check before the first build: the build refused where its estimate
    // (crease_tiles_build_bytes: 18 B a point, 2.5 MB for jacksboro's 403 x 344) does not fit
    // what --max-memory leaves beside the frame check_scene_memory counted, the query throwing that
    const double frame = scene_frame_bytes(scene, t.cols, t.rows);
    scene.terrain.max_memory = std::uint64_t(frame) + (std::uint64_t(1) << 20);
    DrainageLineSource refused = source();
    refused.creases->before_first_decode(crease_tiles_memory_check(scene, t.cols, t.rows));
    try {
        prepare_drainage_lines(refused, view, culling);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::bad_input);
        EXPECT_NE(std::string(e.what()).find("penink: drainage: " + dem.string() +
                                             ": building the crease tiles of a view not drawn before (the drainage "
                                             "grid's 403x344 points) would need about " +
                                             format_bytes(frame + 18.0 * 403 * 344) + " of memory, " +
                                             format_bytes(double(scene.terrain.max_memory)) + " available"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(refused.creases->stems_built(), 0u);
    scene.terrain.max_memory = std::uint64_t(frame) + (std::uint64_t(3) << 20);  // room: built
    EXPECT_NO_THROW(crease_tiles_memory_check(scene, t.cols, t.rows)(t.cols, t.rows));
}

// Without a line test, the stored creases of the whole DEM are the whole build's, and asking again
// builds nothing.
TEST(StoredCreasesRender, AllStemsGiveTheWholeBuild) {
    const test::TempDir dir("stored_creases_all");
    const fs::path dem = example_copy(dir.path, "volcano.asc");
    const Terrain t = read_dem(dem.string());
    DvLineVertices in_file;
    const DrainageDb db = load_or_build_drainage(dem.string(), t, DrainageOptions{}, {}, {}, &in_file);
    ASSERT_FALSE(db.crease_source.empty());
    StoredCreases stored(db.crease_source);
    const DrapedLineSet lines = stored.lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f));
    EXPECT_EQ(stored.stems_built(), stored.stem_count());
    EXPECT_EQ(stored.vertices_built(), lines.vertices.size());
    const DrainageDb whole = build_drainage_db(t, DrainageOptions{});
    EXPECT_TRUE(lines.lines == whole.creases.lines);
    EXPECT_TRUE(lines.vertices == whole.creases.vertices);
    EXPECT_EQ(stored.lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f)).vertices.size(), lines.vertices.size());
    EXPECT_EQ(stored.builds(), 1u);  // kept, not built again
}

}  // namespace
}  // namespace penink
