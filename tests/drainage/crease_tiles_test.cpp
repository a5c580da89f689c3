// Creases built tile by tile on first use (crease_tiles.hpp) give, for any plan box, exactly the
// whole build's lines meeting it (lines_meeting_box on each: the same lines in the same order,
// equal bit for bit), on volcano at its automatic factor and geographic jacksboro, for boxes of
// several sizes at seeded random places, the tiles built in the order the boxes need them; a box
// of a tenth of the DEM's side builds only some tiles, and asking again builds none. With a tile
// store, a second process-like instance reads the tiles the first wrote instead of building them
// and gets the same lines; a tile file damaged (a byte flipped, cut short) or of another key is
// built again and rewritten, the others read.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "drainage/crease_tiles.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/line_tile_files.hpp"
#include "input/dem_reader.hpp"
#include "support/temp_dir.hpp"

namespace penink {
namespace {

bool same_line(const DrapedLineSet& a, std::uint32_t i, const DrapedLineSet& b, std::uint32_t j) {
    const DrapedLine &x = a.lines[i], &y = b.lines[j];
    return std::memcmp(&x.lo, &y.lo, sizeof x.lo) == 0 && std::memcmp(&x.hi, &y.hi, sizeof x.hi) == 0 &&
           std::memcmp(&x.length, &y.length, sizeof x.length) == 0 && x.count == y.count && x.order == y.order &&
           std::memcmp(a.vertices.data() + x.first, b.vertices.data() + y.first, sizeof(DrapedVertex) * x.count) == 0;
}

void expect_boxes_as_whole(const Terrain& t, int factor, int tile, const std::string& what) {
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    ASSERT_FALSE(db.creases.lines.empty()) << what;
    CreaseTiles tiles(g, res.dir, res.net, tile);
    ASSERT_GT(tiles.tile_count(), 8u) << what;
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const DrapedLine& l : db.creases.lines) lo = glm::min(lo, l.lo), hi = glm::max(hi, l.hi);
    const glm::vec2 size = hi - lo;

    // a small box first: some tiles, not all; the same box again: none more
    const glm::vec2 c = lo + 0.5f * size, small = 0.05f * size;
    std::vector<std::uint32_t> ids;
    const DrapedLineSet first = tiles.lines_for_box(c - small, c + small, &ids);
    const std::size_t built = tiles.tiles_built();
    EXPECT_GT(built, 0u) << what;
    EXPECT_LT(built, tiles.tile_count()) << what;
    tiles.lines_for_box(c - small, c + small);
    EXPECT_EQ(tiles.tiles_built(), built) << what;
    ::testing::Test::RecordProperty(what + "_tiles_for_small_box", int(built));
    ::testing::Test::RecordProperty(what + "_tiles", int(tiles.tile_count()));

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::size_t compared = 0, bad = 0;
    for (int k = 0; k < 40; ++k) {
        const float share = k < 10 ? 0.05f : k < 30 ? 0.2f : 0.6f;
        const glm::vec2 a = lo + glm::vec2(u(rng), u(rng)) * size * (1.0f - share), b = a + share * size;
        const DrapedLineSet part = tiles.lines_for_box(a, b, &ids);
        ASSERT_TRUE(line_set_ok(part)) << what;
        const std::vector<std::uint32_t> want = lines_meeting_box(db.creases, a, b);
        const std::vector<std::uint32_t> got = lines_meeting_box(part, a, b);
        ASSERT_EQ(got.size(), want.size()) << what << " box " << k;
        for (std::size_t i = 0; i < got.size(); ++i) {
            ASSERT_EQ(ids[got[i]], want[i]) << what << " box " << k;
            bad += !same_line(part, got[i], db.creases, want[i]), ++compared;
        }
    }
    EXPECT_EQ(bad, 0u) << what;
    EXPECT_GT(compared, db.creases.lines.size()) << what;
}

TEST(CreaseTiles, BoxesGetTheWholeBuildsLines) {
    const Terrain volcano = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    expect_boxes_as_whole(volcano, drainage_resample_factor(volcano, DrainageOptions{}), 64, "volcano_auto");
    const Terrain jacksboro = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    expect_boxes_as_whole(jacksboro, 1, 64, "jacksboro_factor1");
}

// The lines a box gets from `tiles`, mapped to the whole build's: the number differing from it.
std::size_t differing(CreaseTiles& tiles, const DrainageDb& db, glm::vec2 a, glm::vec2 b) {
    std::vector<std::uint32_t> ids;
    const DrapedLineSet part = tiles.lines_for_box(a, b, &ids);
    const std::vector<std::uint32_t> want = lines_meeting_box(db.creases, a, b);
    const std::vector<std::uint32_t> got = lines_meeting_box(part, a, b);
    if (got.size() != want.size()) return std::max(got.size(), want.size());
    std::size_t bad = 0;
    for (std::size_t i = 0; i < got.size(); ++i) bad += ids[got[i]] != want[i] || !same_line(part, got[i], db.creases, want[i]);
    return bad;
}

TEST(CreaseTiles, StoredTilesAreReadByTheNextInstanceAndDamagedOnesRebuilt) {
    const test::TempDir dir;
    const Terrain jacksboro = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    DrainageGrid g = resample_pn(jacksboro, 1);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const DrapedLine& l : db.creases.lines) lo = glm::min(lo, l.lo), hi = glm::max(hi, l.hi);
    const glm::vec2 c = 0.5f * (lo + hi), half = 0.1f * (hi - lo);
    const TileStore store{dir.file("tiles"), 42};

    CreaseTiles first(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(first, db, c - half, c + half), 0u);
    const std::size_t built = first.tiles_built();
    EXPECT_GT(built, 1u);
    EXPECT_EQ(first.tiles_read(), 0u);
    EXPECT_EQ(first.tiles_written(), built);

    CreaseTiles second(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(second, db, c - half, c + half), 0u);
    EXPECT_EQ(second.tiles_read(), built);
    EXPECT_EQ(second.tiles_written(), 0u);

    // one file with a byte flipped in its vertices, one cut short: both built again and rewritten
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(store.folder)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_EQ(files.size(), built);
    {
        std::fstream f(files[0], std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(std::streamoff(std::filesystem::file_size(files[0]) / 2));
        char b = 0;
        f.read(&b, 1);
        b = char(b ^ 0x10);
        f.seekp(std::streamoff(std::filesystem::file_size(files[0]) / 2));
        f.write(&b, 1);
    }
    std::filesystem::resize_file(files[1], std::filesystem::file_size(files[1]) - 3);
    CreaseTiles third(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(third, db, c - half, c + half), 0u);
    EXPECT_EQ(third.tiles_read(), built - 2);
    EXPECT_EQ(third.tiles_written(), 2u);
    CreaseTiles fourth(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(fourth, db, c - half, c + half), 0u);
    EXPECT_EQ(fourth.tiles_read(), built);

    // another key (another network): nothing read
    CreaseTiles other(g, res.dir, res.net, 64, TileStore{store.folder, 43});
    EXPECT_EQ(differing(other, db, c - half, c + half), 0u);
    EXPECT_EQ(other.tiles_read(), 0u);
    EXPECT_EQ(other.tiles_written(), built);
    // a folder that cannot be written: the tiles stay in memory, the lines the same
    CreaseTiles nowhere(g, res.dir, res.net, 64, TileStore{"/proc/penink-no-such-folder", 42});
    EXPECT_EQ(differing(nowhere, db, c - half, c + half), 0u);
    EXPECT_EQ(nowhere.tiles_written(), 0u);
}

}  // namespace
}  // namespace penink
