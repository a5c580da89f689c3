// A render draws the creases `penink drainage` stores the source of (crease_source.hpp) from the
// tiles its view needs: the first render after the database is built builds those tiles and
// writes their files beside the database; a warm render (a new source from the same cache) reads
// exactly those and builds none, and the lines it selects equal the first render's and those of
// a database holding every crease (built in memory) bit for bit; a wider view builds only the
// tiles not yet built; a damaged tile file is built again; several frames asking at once (frames
// prepared on threads) get what one asking alone gets.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/log.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/line_selection.hpp"
#include "drainage/stored_creases.hpp"
#include "input/dem_reader.hpp"
#include "scene/scene.hpp"
#include "scene/terrain_frames.hpp"
#include "support/temp_dir.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

std::size_t files_in(const fs::path& folder) {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(folder)) n += e.is_regular_file();
    return n;
}

bool same_lines(const ScoredLineSet& a, const ScoredLineSet& b) {
    return a.positions.size() == b.positions.size() && a.runs.size() == b.runs.size() &&
           std::memcmp(a.positions.data(), b.positions.data(), sizeof(a.positions[0]) * a.positions.size()) == 0 &&
           std::memcmp(a.normals.data(), b.normals.data(), sizeof(a.normals[0]) * a.normals.size()) == 0 &&
           a.flow == b.flow;
}

TEST(StoredCreasesRender, AWarmRenderBuildsOrReadsOnlyTheTilesItsViewNeeds) {
    const test::TempDir dir("stored_creases");
    const fs::path dem = dir.path / "volcano.asc";
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dem);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir.path / "volcano.prj");
    Scene scene;
    scene.source.dem = dem.string();
    const Terrain t = read_dem(dem.string());
    const fs::path tiles = crease_tile_folder(drainage_cache_path(dem.string()));

    std::optional<DrainageLineSource> first = scene_drainage(scene, t, Log{});  // builds and writes the cache
    ASSERT_TRUE(first && first->creases);
    LineBox all = line_box(t), view = all;
    const glm::vec2 size = all.hi - all.lo;  // a tenth of the side, near a corner
    view.lo = all.lo + 0.1f * size, view.hi = all.lo + 0.2f * size;
    const DrainageLineData a = prepare_drainage_lines(*first, view);
    const std::size_t needed = first->creases->tiles_built();
    ASSERT_GT(a.creases.positions.size(), 100u);
    EXPECT_GT(needed, 0u);
    EXPECT_LT(needed, first->creases->tile_count());
    EXPECT_EQ(first->creases->tiles_read(), 0u);
    EXPECT_EQ(files_in(tiles), needed);
    RecordProperty("tiles", int(first->creases->tile_count()));
    RecordProperty("tiles_for_view", int(needed));

    // a database holding every crease draws the same
    const DrainageDb whole = build_drainage_db(t, DrainageOptions{});
    ASSERT_TRUE(whole.crease_source.empty());
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, view).creases, a.creases));

    // a warm render: reads the view's tiles, builds none
    std::optional<DrainageLineSource> warm = scene_drainage(scene, t, Log{});
    ASSERT_TRUE(warm && warm->creases && warm->vertices.file);
    const DrainageLineData b = prepare_drainage_lines(*warm, view);
    EXPECT_EQ(warm->creases->tiles_read(), needed);
    EXPECT_EQ(warm->creases->tiles_built(), 0u);
    EXPECT_TRUE(same_lines(a.creases, b.creases));
    EXPECT_TRUE(same_lines(a.ridges, b.ridges));
    // the whole DEM: the other tiles built, those read kept
    const DrainageLineData w = prepare_drainage_lines(*warm, all);
    EXPECT_EQ(warm->creases->tiles_read(), needed);
    EXPECT_EQ(warm->creases->tiles_built(), warm->creases->tile_count() - needed);
    EXPECT_TRUE(same_lines(prepare_drainage_lines(whole, all).creases, w.creases));

    // a damaged tile file is built again, the others read
    fs::path one;
    for (const auto& e : fs::directory_iterator(tiles)) one = e.path();
    {
        std::fstream f(one, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(40);
        f.put('\x5a');
    }
    std::optional<DrainageLineSource> again = scene_drainage(scene, t, Log{});
    EXPECT_TRUE(same_lines(prepare_drainage_lines(*again, all).creases, w.creases));
    EXPECT_EQ(again->creases->tiles_built(), 1u);
    EXPECT_EQ(again->creases->tiles_read(), again->creases->tile_count() - 1);

    // frames on threads share one source: each gets what it gets alone
    std::optional<DrainageLineSource> shared = scene_drainage(scene, t, Log{});
    std::vector<DrainageLineData> got(4);
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < got.size(); ++k)
        threads.emplace_back([&, k] { got[k] = prepare_drainage_lines(*shared, k % 2 ? all : view); });
    for (std::thread& th : threads) th.join();
    for (std::size_t k = 0; k < got.size(); ++k) EXPECT_TRUE(same_lines(got[k].creases, (k % 2 ? w : a).creases)) << k;
}

// A cache folder that cannot be written keeps the tiles in memory: the creases are the same.
TEST(StoredCreasesRender, AnUnwritableTileFolderKeepsTilesInMemory) {
    const test::TempDir dir("stored_creases_ro");
    const fs::path dem = dir.path / "volcano.asc";
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dem);
    const Terrain t = read_dem(dem.string());
    DvLineVertices in_file;
    const DrainageDb db = load_or_build_drainage(dem.string(), t, DrainageOptions{}, {}, {}, &in_file);
    ASSERT_FALSE(db.crease_source.empty());
    std::ofstream(dir.path / "file") << "x";  // a folder under a regular file cannot be made
    StoredCreases stored(db.crease_source, (dir.path / "file" / "tiles").string());
    const DrapedLineSet lines = stored.lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f));
    EXPECT_EQ(stored.tiles_built(), stored.tile_count());
    const DrainageDb whole = build_drainage_db(t, DrainageOptions{});
    EXPECT_TRUE(lines.lines == whole.creases.lines);
    EXPECT_TRUE(lines.vertices == whole.creases.vertices);
    EXPECT_EQ(stored.lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f)).vertices.size(), lines.vertices.size());
    EXPECT_EQ(stored.tiles_built(), stored.tile_count());  // kept, not built again
}

}  // namespace
}  // namespace penink
