// Creases built tile by tile on first use (crease_tiles.hpp) give, for any plan box, exactly the
// whole build's lines meeting it (lines_meeting_box on each: the same lines in the same order,
// equal bit for bit), on volcano at its automatic factor and geographic jacksboro, for boxes of
// several sizes at seeded random places, the tiles built in the order the boxes need them; a box
// of a tenth of the DEM's side builds only some tiles, and asking again builds none.
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "drainage/crease_tiles.hpp"
#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"

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

}  // namespace
}  // namespace penink
