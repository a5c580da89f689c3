// Creases built tile by tile on first use (crease_tiles.hpp) give, for any plan box, exactly the
// whole build's lines meeting it (lines_meeting_box on each: the same lines in the same order,
// equal bit for bit), on volcano at its automatic factor and geographic jacksboro, for boxes of
// several sizes at seeded random places, the stems built in the order the boxes need them; a box
// of a tenth of the DEM's side builds only some stems, and asking again builds none. With a line
// test (a camera's screen size), only the stems whose bound passes it are built, once.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "drainage/crease_tiles.hpp"
#include "drainage/drainage_build.hpp"
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
    const std::size_t built = tiles.stems_built();
    EXPECT_GT(built, 0u) << what;
    EXPECT_LT(built, tiles.stem_count()) << what;
    tiles.lines_for_box(c - small, c + small);
    EXPECT_EQ(tiles.stems_built(), built) << what;
    EXPECT_EQ(tiles.builds(), 1u) << what;
    ::testing::Test::RecordProperty(what + "_stems_for_small_box", int(built));
    ::testing::Test::RecordProperty(what + "_stems", int(tiles.stem_count()));

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

// The index made and coded a row of tiles at a time is the whole index coded, unit for unit and
// byte for byte: tile boxes, units (their order, counts, boxes and largest bounds) and each unit's
// coded ids and bounds; on jacksboro at factor 1 (rows of tiles of 16, 64 and 100 cells, the last
// row cut) and the volcano at factor 5 (a grid of 301 x 431 points).
TEST(CreaseTiles, IndexCodedByRowsIsTheWholeIndexCoded) {
    const Terrain jacksboro = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    const Terrain volcano = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    for (const auto& [t, factor, tile] : {std::tuple(&jacksboro, 1, 16), std::tuple(&jacksboro, 1, 64),
                                          std::tuple(&jacksboro, 1, 100), std::tuple(&volcano, 5, 64)}) {
        const std::string what = std::to_string(factor) + "/" + std::to_string(tile);
        DrainageGrid g = resample_pn(*t, factor);
        DrainageResult res;
        drainage_db_from_grid(g, {}, &res);
        const CodedCreaseIndex whole = code_crease_index(crease_tile_index(g, res.dir, res.net, tile), g.cols, g.rows, g.dx);
        const CodedCreaseIndex rows = coded_crease_tile_index(g, res.dir, res.net, tile);
        ASSERT_GT(whole.index.lo.size() / std::size_t((g.cols + tile - 1) / tile), 2u) << what;  // rows of tiles
        EXPECT_TRUE(whole.index.stems.empty() && rows.index.stems.empty()) << what;
        EXPECT_EQ(rows.index.side, tile) << what;
        EXPECT_EQ(rows.index.parts.sources, whole.index.parts.sources) << what;
        EXPECT_EQ(rows.index.parts.lo, whole.index.parts.lo) << what;
        EXPECT_EQ(rows.index.parts.hi, whole.index.parts.hi) << what;
        EXPECT_EQ(rows.index.lo, whole.index.lo) << what;
        EXPECT_EQ(rows.index.hi, whole.index.hi) << what;
        EXPECT_EQ(rows.index.z_top, whole.index.z_top) << what;
        ASSERT_GT(whole.index.units.size(), 20u) << what;
        EXPECT_TRUE(rows.index.units == whole.index.units) << what;
        EXPECT_TRUE(rows.ids == whole.ids) << what;
        EXPECT_TRUE(rows.bounds == whole.bounds) << what;
    }
}

// A line test as a perspective camera's screen size makes it, at exaggeration e: a line passes
// when its length is at least `per_metre` times its box's plan distance from `eye` (a longer line
// or a box nearer the eye passes sooner); a stem's bound passes with its length at e
// (stem_bound_length) in its box, a line with its length exaggerated by e (from its vertices).
struct SizeTest {
    glm::vec2 eye;
    double per_metre = 0.0, e = 1.0;
    bool passes(glm::vec2 lo, glm::vec2 hi, double length) const {
        const double dx = std::max({double(lo.x) - eye.x, double(eye.x) - hi.x, 0.0});
        const double dy = std::max({double(lo.y) - eye.y, double(eye.y) - hi.y, 0.0});
        return length >= per_metre * std::sqrt(dx * dx + dy * dy);
    }
    bool line(const DrapedLineSet& set, std::uint32_t i) const {
        const DrapedLine& l = set.lines[i];
        double length = 0.0;
        for (std::uint32_t k = l.first + 1; k < l.first + l.count; ++k) {
            const DrapedVertex &a = set.vertices[k - 1], &b = set.vertices[k];
            length += std::sqrt(std::pow(double(b.x) - double(a.x), 2) + std::pow(double(b.y) - double(a.y), 2) +
                                std::pow(e * (double(b.z) - double(a.z)), 2));
        }
        return passes(l.lo, l.hi, length);
    }
    CreaseTiles::LineTest bound() const {
        return [t = *this](const StemBound& b, glm::vec2 lo, glm::vec2 hi, float) {
            return t.passes(lo, hi, stem_bound_length(b, t.e));
        };
    }
};

// The lines a box gets from `tiles` with the line test `t`, mapped to the whole build's lines
// meeting the box that pass it: the number differing from them.
std::size_t differing(CreaseTiles& tiles, const DrainageDb& db, glm::vec2 a, glm::vec2 b,
                      const SizeTest& t) {
    std::vector<std::uint32_t> ids;
    const DrapedLineSet part = tiles.lines_for_box(a, b, &ids, t.bound());
    std::vector<std::uint32_t> want;
    for (std::uint32_t i : lines_meeting_box(db.creases, a, b))
        if (t.line(db.creases, i)) want.push_back(i);
    std::vector<std::uint32_t> got;
    for (std::uint32_t i : lines_meeting_box(part, a, b))
        if (t.line(part, i)) got.push_back(i);
    if (got.size() != want.size()) return std::max(got.size(), want.size());
    std::size_t bad = 0;
    for (std::size_t i = 0; i < got.size(); ++i) bad += ids[got[i]] != want[i] || !same_line(part, got[i], db.creases, want[i]);
    return bad;
}

// Jacksboro's network at factor 1, its whole build and the box of its creases.
struct JacksboroNetwork {
    DrainageGrid g;
    DrainageResult res;
    DrainageDb db;
    glm::vec2 lo{1e30f}, hi{-1e30f};
    JacksboroNetwork() {
        g = resample_pn(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 1);
        db = drainage_db_from_grid(g, {}, &res);
        for (const DrapedLine& l : db.creases.lines) lo = glm::min(lo, l.lo), hi = glm::max(hi, l.hi);
    }
};

// With a line test, a query builds only the stems whose bound passes it (counted from the index),
// and gets exactly the whole build's lines that pass it; a laxer test later builds only the
// stems it adds, in one more build; asking again builds none.
TEST(CreaseTiles, ALineTestBuildsOnlyTheStemsItPassesOnce) {
    const JacksboroNetwork n;
    const DrainageGrid& g = n.g;
    const DrainageResult& res = n.res;
    const DrainageDb& db = n.db;
    const glm::vec2 lo = n.lo, hi = n.hi;
    CreaseTiles tiles(g, res.dir, res.net, 64);
    const CreaseTileIndex index = tiles.index();
    // the stems whose bound passes a test, and the whole build's lines that do
    auto bounds_passing = [&](const SizeTest& t) {
        std::size_t count = 0;
        for (const StemBound& b : index.stems) {
            glm::vec2 blo, bhi;
            stem_bound_box(b, index.parts.lo, index.parts.hi, blo, bhi);
            count += t.bound()(b, blo, bhi, index.z_top);
        }
        return count;
    };
    auto lines_passing = [&](const SizeTest& t) {
        std::size_t count = 0;
        for (std::uint32_t i = 0; i < db.creases.lines.size(); ++i) count += t.line(db.creases, i);
        return count;
    };
    const SizeTest strict{lo, 0.05, 2.0}, lax{lo, 0.02, 2.0};
    const std::size_t strict_stems = bounds_passing(strict), lax_stems = bounds_passing(lax);
    ASSERT_GT(lines_passing(strict), 100u);
    EXPECT_LT(strict_stems, tiles.stem_count() / 2);
    EXPECT_GT(lax_stems, strict_stems);
    EXPECT_GE(strict_stems, lines_passing(strict));

    EXPECT_EQ(differing(tiles, db, lo, hi, strict), 0u);
    EXPECT_EQ(tiles.stems_built(), strict_stems);
    EXPECT_EQ(tiles.builds(), 1u);
    EXPECT_EQ(differing(tiles, db, lo, hi, lax), 0u);
    EXPECT_EQ(tiles.stems_built(), lax_stems);
    EXPECT_EQ(tiles.builds(), 2u);
    EXPECT_EQ(differing(tiles, db, lo, hi, strict), 0u);
    EXPECT_EQ(differing(tiles, db, lo, hi, lax), 0u);
    EXPECT_EQ(tiles.builds(), 2u);
    ::testing::Test::RecordProperty("stems", int(tiles.stem_count()));
    ::testing::Test::RecordProperty("stems_strict", int(strict_stems));
    ::testing::Test::RecordProperty("lines_strict", int(lines_passing(strict)));
    ::testing::Test::RecordProperty("stems_lax", int(lax_stems));
    ::testing::Test::RecordProperty("lines_lax", int(lines_passing(lax)));
}

// With a tile store, the levels of the tiles a query needs are built whole and written, a file
// each; the next instance reads them and builds nothing, keeping only the stems the test passes;
// a file damaged (a byte flipped, cut short) is built again and rewritten, a file of another key
// is not read; a folder that cannot be written keeps the stems in memory; an index of units alone
// needs the whole one only where a file fails. The lines are the whole build's throughout.
TEST(CreaseTiles, StoredTilesAreReadByTheNextInstanceAndDamagedOnesRebuilt) {
    const test::TempDir dir;
    const JacksboroNetwork n;
    const DrainageGrid& g = n.g;
    const DrainageResult& res = n.res;
    const DrainageDb& db = n.db;
    const glm::vec2 lo = n.lo, hi = n.hi;
    const SizeTest strict{lo, 0.05, 2.0};
    const TileStore store{dir.file("tiles"), 42};

    CreaseTiles first(g, res.dir, res.net, 64, store);
    std::vector<double> shown;  // the build's progress: rising to 1
    first.on_build_progress([&](double f) { shown.push_back(f); });
    EXPECT_EQ(differing(first, db, lo, hi, strict), 0u);
    ASSERT_GT(shown.size(), 2u);
    EXPECT_TRUE(std::is_sorted(shown.begin(), shown.end()));
    EXPECT_GT(shown.front(), 0.0);
    EXPECT_EQ(shown.back(), 1.0);
    const std::size_t built = first.tiles_built(), kept = first.stems_built();
    EXPECT_GT(built, 4u);
    EXPECT_EQ(first.tiles_read(), 0u);
    EXPECT_EQ(first.tiles_written(), built);
    // a level of a tile is built whole, but only the stems passing are kept
    EXPECT_LT(kept, first.stem_count() / 2);
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(store.folder)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_EQ(files.size(), built);
    // the long stems' levels are fewer than the tiles times the levels: the strict test passes none
    // of the shortest stems far from the eye
    EXPECT_LT(built, first.tile_count() * std::size_t(crease_tile_levels));

    CreaseTiles second(g, res.dir, res.net, 64, store);
    shown.clear();
    second.on_build_progress([&](double f) { shown.push_back(f); });
    EXPECT_EQ(differing(second, db, lo, hi, strict), 0u);
    EXPECT_TRUE(shown.empty());  // nothing built
    EXPECT_EQ(second.tiles_read(), built);
    EXPECT_EQ(second.tiles_built(), 0u);
    EXPECT_EQ(second.stems_built(), kept);

    {  // one file with a byte flipped in its vertices, one cut short: both built again and rewritten
        std::fstream f(files[0], std::ios::in | std::ios::out | std::ios::binary);
        const auto at = std::streamoff(std::filesystem::file_size(files[0]) / 2);
        f.seekg(at);
        char b = 0;
        f.read(&b, 1);
        b = char(b ^ 0x10);
        f.seekp(at);
        f.write(&b, 1);
    }
    std::filesystem::resize_file(files[1], std::filesystem::file_size(files[1]) - 3);
    CreaseTiles third(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(third, db, lo, hi, strict), 0u);
    EXPECT_EQ(third.tiles_read(), built - 2);
    EXPECT_EQ(third.tiles_written(), 2u);
    CreaseTiles fourth(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(fourth, db, lo, hi, strict), 0u);
    EXPECT_EQ(fourth.tiles_read(), built);
    for (int frame = 0; frame < 20; ++frame) differing(fourth, db, lo, hi, strict);  // a flight's frames
    EXPECT_EQ(fourth.tiles_read(), 21 * built);
    EXPECT_LE(fourth.sets_held(), 2 * built);  // the sets each frame read and forgot do not pile up

    // an index of its units alone: the files read, their stems tested by the bounds they carry; a
    // unit without a file (none of its stems passed before) tested by its stems' bounds alone; the
    // whole index never asked for; a file gone: asked for once, that level built and written
    CreaseTileIndex units = first.index();
    const CreaseTileIndex whole = units;
    const std::vector<std::vector<std::uint32_t>> members = crease_unit_stems(whole, g.cols, g.rows, g.dx);
    units.parts.sources.clear(), units.stems.clear();
    std::atomic<int> asked{0}, asked_units{0};
    CreaseIndexReader reader;
    reader.unit = [&](std::size_t u, std::vector<std::uint32_t>& ids, std::vector<StemBound>& bounds) {
        ++asked_units;
        ids = members.at(u), bounds.clear();
        for (std::uint32_t s : ids) bounds.push_back(whole.stems[s]);
    };
    reader.whole = [&] {
        ++asked;
        return whole;
    };
    CreaseTiles lazy(g, res.dir, res.net, units, store, reader);
    EXPECT_EQ(lazy.stem_count(), first.stem_count());
    EXPECT_EQ(differing(lazy, db, lo, hi, strict), 0u);
    EXPECT_EQ(asked, 0);
    EXPECT_FALSE(lazy.index_loaded());
    EXPECT_EQ(lazy.tiles_read(), built);
    EXPECT_EQ(lazy.stems_built(), kept);
    EXPECT_GT(asked_units, 0);  // the strict test's summaries pass some units whose stems all fail
    std::filesystem::remove(files[2]);
    CreaseTiles lazy_gone(g, res.dir, res.net, units, store, reader);
    EXPECT_EQ(differing(lazy_gone, db, lo, hi, strict), 0u);
    EXPECT_EQ(asked, 1);
    EXPECT_TRUE(lazy_gone.index_loaded());
    EXPECT_EQ(lazy_gone.tiles_read(), built - 1);
    EXPECT_EQ(lazy_gone.tiles_written(), 1u);
    EXPECT_EQ(differing(lazy_gone, db, lo, hi, strict), 0u);  // again: from the files, the index kept
    EXPECT_EQ(asked, 1);
    // with a reader of the stems' sources: a file gone is built from its unit's block and the
    // sources alone, the whole index never asked for
    std::atomic<int> asked_sources{0};
    reader.sources = [&] {
        ++asked_sources;
        return whole.parts.sources;
    };
    std::filesystem::remove(files[2]);
    CreaseTiles lazy_sources(g, res.dir, res.net, units, store, reader);
    EXPECT_EQ(differing(lazy_sources, db, lo, hi, strict), 0u);
    EXPECT_EQ(asked, 1);
    EXPECT_EQ(asked_sources, 1);
    EXPECT_FALSE(lazy_sources.index_loaded());
    EXPECT_EQ(lazy_sources.tiles_read(), built - 1);
    EXPECT_EQ(lazy_sources.tiles_written(), 1u);
    EXPECT_EQ(differing(lazy_sources, db, lo, hi, strict), 0u);  // again: from the files
    EXPECT_EQ(asked_sources, 1);
    EXPECT_EQ(lazy_sources.tiles_read(), 2 * built - 1);

    // another key (another network): nothing read
    CreaseTiles other(g, res.dir, res.net, 64, TileStore{store.folder, 43});
    EXPECT_EQ(differing(other, db, lo, hi, strict), 0u);
    EXPECT_EQ(other.tiles_read(), 0u);
    EXPECT_EQ(other.tiles_written(), built);
    // a folder that cannot be written: the stems stay in memory, the lines the same; every stem
    // whose index bound passes is kept (a later query may pass others by their lines' bounds),
    // where the files keep only those whose line's bound passes too
    CreaseTiles nowhere(g, res.dir, res.net, 64, TileStore{"/proc/penink-no-such-folder", 42});
    EXPECT_EQ(differing(nowhere, db, lo, hi, strict), 0u);
    EXPECT_EQ(nowhere.tiles_written(), 0u);
    CreaseTiles in_memory(g, res.dir, res.net, 64);
    EXPECT_EQ(differing(in_memory, db, lo, hi, strict), 0u);
    EXPECT_EQ(nowhere.stems_built(), in_memory.stems_built());
    EXPECT_LT(kept, in_memory.stems_built());
}

// The files in a tile store that hold some of their unit's stems, not all (crease_partial_share),
// and all files, of detail 0 (copies: `copies` true, the copies alone).
struct StoreFiles {
    std::size_t some = 0, all = 0;
};
StoreFiles files_of_some_stems(const std::string& folder, const CreaseTileIndex& index, bool copies = false) {
    StoreFiles out;
    for (const auto& e : std::filesystem::directory_iterator(folder)) {
        const std::string name = e.path().filename().string();  // tile-K-L.pnlt or tile-K-L-dD.pnlt
        unsigned k = 0, l = 0, d = 0;
        const int fields = std::sscanf(name.c_str(), "tile-%u-%u-d%u.pnlt", &k, &l, &d);
        if ((fields == 3) != copies || fields < 2) continue;
        std::ifstream f(e.path(), std::ios::binary);
        std::uint64_t key = 0;  // (its own: the header's, after the magic and version)
        f.seekg(8);
        f.read(reinterpret_cast<char*>(&key), sizeof key);
        TileLines lines;
        if (!read_line_tile(e.path().string(), key, lines)) continue;
        const auto u = std::find_if(index.units.begin(), index.units.end(),
                                    [&](const CreaseUnit& c) { return c.tile == k && c.level == l; });
        if (u == index.units.end()) continue;
        ++out.all, out.some += lines.stems.size() < u->count;
    }
    return out;
}

// A unit whose stems a query needs weigh crease_partial_share of it or less is built and written
// with those alone: the next instance with the same test reads its file (from an index of units
// alone too) and builds nothing; one with a laxer test needing stems the file lacks builds that
// unit whole and writes it over, and the next one builds nothing; at a detail, a copy of some of
// the stems gives way to the whole file at detail 0, thinned and written again. The lines are the
// whole build's throughout.
TEST(CreaseTiles, UnitsWhoseStemsAreFewNeededAreWrittenWithThoseAlone) {
    const JacksboroNetwork n;
    const auto& [g, res, db, lo, hi] = n;
    const SizeTest strict{lo, 0.05, 2.0}, lax{lo, 0.02, 2.0};
    const test::TempDir dir;
    const TileStore store{dir.file("tiles"), 42};

    CreaseTiles first(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(first, db, lo, hi, strict), 0u);
    const CreaseTileIndex whole = first.index();
    const StoreFiles strict_files = files_of_some_stems(store.folder, whole);
    EXPECT_GT(strict_files.some, 2u);
    EXPECT_LT(strict_files.some, strict_files.all);  // others whole
    EXPECT_EQ(strict_files.all, first.tiles_written());
    // the stems built: fewer than their units hold
    std::size_t in_units = 0;
    for (const auto& e : std::filesystem::directory_iterator(store.folder)) {
        unsigned k = 0, l = 0;
        if (std::sscanf(e.path().filename().string().c_str(), "tile-%u-%u", &k, &l) != 2) continue;
        for (const CreaseUnit& u : whole.units) in_units += u.tile == k && u.level == l ? u.count : 0;
    }
    EXPECT_LT(first.stems_built(), in_units);

    // an index of its units alone, the same test: every file read, nothing built
    CreaseTileIndex units = whole;
    const std::vector<std::vector<std::uint32_t>> members = crease_unit_stems(whole, g.cols, g.rows, g.dx);
    units.parts.sources.clear(), units.stems.clear();
    CreaseIndexReader reader;
    std::atomic<int> asked_units{0};
    reader.unit = [&](std::size_t u, std::vector<std::uint32_t>& ids, std::vector<StemBound>& bounds) {
        ++asked_units;
        ids = members.at(u), bounds.clear();
        for (std::uint32_t s : ids) bounds.push_back(whole.stems[s]);
    };
    reader.whole = [&] { return whole; };
    reader.sources = [&] { return whole.parts.sources; };
    CreaseTiles lazy(g, res.dir, res.net, units, store, reader);
    EXPECT_EQ(differing(lazy, db, lo, hi, strict), 0u);
    EXPECT_EQ(lazy.tiles_built(), 0u);
    EXPECT_EQ(lazy.tiles_read(), strict_files.all);
    EXPECT_FALSE(lazy.index_loaded());
    // the files of some stems read by what bounds the stems they leave out: the index's blocks
    // asked for by the units without a file (whose summary passes but no stem), not by those files
    std::size_t passing_units = 0;
    for (const CreaseUnit& u : whole.units) {
        glm::vec2 ulo = u.lo, uhi = u.hi;
        passing_units += strict.bound()(u.most, ulo, uhi, whole.z_top);
    }
    ASSERT_GT(passing_units, strict_files.all);
    EXPECT_EQ(std::size_t(asked_units), passing_units - strict_files.all);
    ::testing::Test::RecordProperty("asked_units", int(asked_units));

    // a laxer test: the units whose files lack stems it needs built whole and written over
    CreaseTiles laxer(g, res.dir, res.net, units, store, reader);
    EXPECT_EQ(differing(laxer, db, lo, hi, lax), 0u);
    EXPECT_GT(laxer.tiles_built(), 0u);
    EXPECT_LT(files_of_some_stems(store.folder, whole).some + strict_files.all - strict_files.some,
              files_of_some_stems(store.folder, whole).all + 1);
    CreaseTiles laxer_again(g, res.dir, res.net, 64, store);
    EXPECT_EQ(differing(laxer_again, db, lo, hi, lax), 0u);
    EXPECT_EQ(laxer_again.tiles_built(), 0u);
    EXPECT_EQ(differing(laxer_again, db, lo, hi, strict), 0u);

    // at detail 2: copies of some stems, then the units made whole at detail 0 by a laxer test;
    // the copies then give way to the files, thinned and written again, and are read after
    const TileStore thin_store{dir.file("thin"), 42};
    const CreaseTiles::LineDetail detail = [&](glm::vec2, glm::vec2, float) { return 4.5 * g.dx; };
    const DrapedLineSet want = thinned_lines(db.creases, 4.0 * g.dx);
    const auto bad_lines = [&](CreaseTiles& tiles, const SizeTest& t, const CreaseTiles::LineDetail& d) {
        std::vector<std::uint32_t> ids;
        const DrapedLineSet got = tiles.lines_for_box(lo, hi, &ids, t.bound(), d);
        std::size_t bad = ids.size() < 100;
        for (std::uint32_t i = 0; i < ids.size(); ++i) bad += !same_line(got, i, d ? want : db.creases, ids[i]);
        return bad;
    };
    CreaseTiles thin(g, res.dir, res.net, 64, thin_store);
    EXPECT_EQ(bad_lines(thin, strict, detail), 0u);
    const StoreFiles copies = files_of_some_stems(thin_store.folder, whole, true);
    EXPECT_GT(copies.some, 2u);
    CreaseTiles full(g, res.dir, res.net, 64, thin_store);
    EXPECT_EQ(bad_lines(full, lax, {}), 0u);
    EXPECT_GT(full.tiles_built(), 0u);
    EXPECT_EQ(files_of_some_stems(thin_store.folder, whole, true).some, copies.some);  // (not rewritten yet)
    // the test the copies were written for: they hold every stem it needs and are read alone,
    // not the files of more stems beside them (thinned and written again), from the index or
    // from its units alone
    for (const bool from_units : {false, true}) {
        std::unique_ptr<CreaseTiles> again = from_units ? std::make_unique<CreaseTiles>(g, res.dir, res.net, units, thin_store, reader)
                                                        : std::make_unique<CreaseTiles>(g, res.dir, res.net, 64, thin_store);
        EXPECT_EQ(bad_lines(*again, strict, detail), 0u) << from_units;
        EXPECT_EQ(again->tiles_built(), 0u) << from_units;
        EXPECT_EQ(again->tiles_written(), 0u) << from_units;
        EXPECT_EQ(files_of_some_stems(thin_store.folder, whole, true).some, copies.some) << from_units;
    }
    CreaseTiles thin_lax(g, res.dir, res.net, 64, thin_store);
    EXPECT_EQ(bad_lines(thin_lax, lax, detail), 0u);
    EXPECT_EQ(thin_lax.tiles_built(), 0u);
    EXPECT_GT(thin_lax.tiles_written(), 0u);  // copies thinned from the files
    EXPECT_LT(files_of_some_stems(thin_store.folder, whole, true).some, copies.some);
    CreaseTiles thin_read(g, res.dir, res.net, 64, thin_store);
    EXPECT_EQ(bad_lines(thin_read, lax, detail), 0u);
    EXPECT_EQ(thin_read.tiles_built(), 0u);
    EXPECT_EQ(thin_read.tiles_written(), 0u);
}

// A stem's line bound (crease_line_bound) passes a screen-size test wherever its line does, is
// never looser than its index bound, and passes far fewer stems on a distant view: the lines a
// query gives are those whose line bound passes, whether read, built or kept from before.
TEST(CreaseTiles, LineBoundsHoldTheirLinesAndPassFewerStems) {
    const JacksboroNetwork n;
    const DrainageDb& db = n.db;
    CreaseTiles tiles(n.g, n.res.dir, n.res.net, 64);
    const CreaseTileIndex index = tiles.index();
    ASSERT_EQ(index.stems.size(), db.creases.lines.size());
    std::size_t line_pass = 0, index_pass = 0, tight_pass = 0;
    for (const SizeTest& t : {SizeTest{n.lo, 0.05, 2.0}, SizeTest{n.lo, 0.02, 0.5}}) {
        for (std::uint32_t i = 0; i < index.stems.size(); ++i) {
            const StemBound& reach = index.stems[i];
            const StemBound b = crease_line_bound(db.creases, i, reach, index.parts.lo, index.parts.hi);
            ASSERT_LE(b.plan, reach.plan);
            ASSERT_LE(b.rise, reach.rise);
            glm::vec2 blo, bhi, rlo, rhi;
            stem_bound_box(b, index.parts.lo, index.parts.hi, blo, bhi);
            stem_bound_box(reach, index.parts.lo, index.parts.hi, rlo, rhi);
            ASSERT_TRUE(blo.x >= rlo.x && blo.y >= rlo.y && bhi.x <= rhi.x && bhi.y <= rhi.y) << i;
            const DrapedLine& l = db.creases.lines[i];
            ASSERT_TRUE(blo.x <= l.lo.x && blo.y <= l.lo.y && bhi.x >= l.hi.x && bhi.y >= l.hi.y) << i;
            const bool line = t.line(db.creases, i), tight = t.bound()(b, blo, bhi, index.z_top),
                       loose = t.bound()(reach, rlo, rhi, index.z_top);
            ASSERT_TRUE(!line || tight) << i;
            ASSERT_TRUE(!tight || loose) << i;
            line_pass += line, tight_pass += tight, index_pass += loose;
        }
    }
    ASSERT_GT(line_pass, 100u);
    EXPECT_LT(double(tight_pass), 0.8 * double(index_pass));
    ::testing::Test::RecordProperty("lines_passing", int(line_pass));
    ::testing::Test::RecordProperty("line_bounds_passing", int(tight_pass));
    ::testing::Test::RecordProperty("index_bounds_passing", int(index_pass));
}

// Thinning keeps each line's ends and the vertices a spacing apart, and gives a thinned line back
// unchanged.
TEST(CreaseTiles, ThinnedLinesKeepEndsAndSpacing) {
    const JacksboroNetwork n;
    const DrapedLineSet& all = n.db.creases;
    const double spacing = 4.0 * n.g.dx;
    const DrapedLineSet thin = thinned_lines(all, spacing);
    ASSERT_EQ(thin.lines.size(), all.lines.size());
    ASSERT_TRUE(line_set_ok(thin));
    EXPECT_LT(thin.vertices.size(), all.vertices.size() * 3 / 4);  // 0.59 measured: short stems keep both ends
    std::size_t bad = 0;
    for (std::size_t i = 0; i < all.lines.size(); ++i) {
        const DrapedLine &a = all.lines[i], &t = thin.lines[i];
        const DrapedVertex* v = thin.vertices.data() + t.first;
        bad += !(v[0] == all.vertices[a.first] && v[t.count - 1] == all.vertices[a.first + a.count - 1]);
        bad += t.order != a.order || t.count > a.count || (a.count >= 2 && t.count < 2);
        for (std::uint32_t k = 1; k + 1 < t.count; ++k) {  // inner vertices a spacing or more apart
            const glm::dvec3 p(v[k].x, v[k].y, v[k].z), q(v[k - 1].x, v[k - 1].y, v[k - 1].z);
            bad += glm::length(p - q) < spacing * (1.0 - 1e-9);
        }
    }
    EXPECT_EQ(bad, 0u);
    EXPECT_TRUE(thinned_lines(thin, spacing) == thin);
}

// A query a row of tiles at a time gives, row after row, the lines of one query in its order
// (stems numbered by source cell), built or read from the files, at their units' detail; one
// query for builds().
TEST(CreaseTiles, RowsOfTilesGiveTheQuerysLinesInItsOrder) {
    const test::TempDir dir;
    const JacksboroNetwork n;
    const SizeTest loose{n.lo, 0.05, 0.5};
    const CreaseTiles::LineDetail detail = [&](glm::vec2, glm::vec2, float) { return 2.5 * n.g.dx; };
    const TileStore store{dir.file("tiles"), 7};
    for (int pass = 0; pass < 2; ++pass) {  // built and written, then read from the files
        CreaseTiles one(n.g, n.res.dir, n.res.net, 64, store), by_row(n.g, n.res.dir, n.res.net, 64, store);
        std::vector<double> shown;  // the build's progress over the whole query: rising to 1
        by_row.on_build_progress([&](double f) { shown.push_back(f); });
        std::vector<CreaseTiles::LineRefs> got_rows;  // (by rows first: the first pass builds them)
        by_row.line_refs_by_row(n.lo, n.hi, loose.bound(), detail,
                                [&](CreaseTiles::LineRefs got) { got_rows.push_back(std::move(got)); });
        const DrapedLineSet want = one.lines_for_box(n.lo, n.hi, nullptr, loose.bound(), detail);
        ASSERT_GT(want.lines.size(), 100u);
        std::size_t at = 0, rows = 0, rows_with_lines = 0;
        for (const CreaseTiles::LineRefs& got : got_rows) {
            ++rows, rows_with_lines += !got.lines.empty();
            for (std::size_t i = 0; i < got.lines.size(); ++i, ++at) {
                ASSERT_LT(at, want.lines.size());
                const DrapedLine &a = got.lines[i], &b = want.lines[at];
                ASSERT_EQ(a.count, b.count) << at;
                EXPECT_EQ(std::memcmp(&a.lo, &b.lo, sizeof a.lo), 0) << at;
                EXPECT_EQ(std::memcmp(&a.length, &b.length, sizeof a.length), 0) << at;
                EXPECT_EQ(std::memcmp(got.vertices[i], want.vertices.data() + b.first, sizeof(DrapedVertex) * a.count), 0) << at;
            }
        }
        EXPECT_EQ(at, want.lines.size());
        EXPECT_EQ(rows, std::size_t((n.g.rows + 63) / 64));
        EXPECT_GT(rows_with_lines, 3u);
        EXPECT_EQ(by_row.builds(), 1u);
        EXPECT_EQ(by_row.stems_built(), one.stems_built());
        if (pass == 1) {
            EXPECT_EQ(by_row.tiles_written(), 0u);
            EXPECT_TRUE(shown.empty());  // nothing built
            EXPECT_EQ(one.tiles_written(), 0u);
        } else {
            ASSERT_GT(shown.size(), 4u);
            EXPECT_TRUE(std::is_sorted(shown.begin(), shown.end()));
            EXPECT_GT(shown.front(), 0.0);
            EXPECT_LT(shown.front(), 0.5);
            EXPECT_EQ(shown.back(), 1.0);
            EXPECT_EQ(std::count(shown.begin(), shown.end(), 1.0), 1);
        }
    }
}

// With a line detail, every line comes at its unit's detail: the whole build's line thinned to
// that detail's spacing, bit for bit, its vertices on the creases' lattice (what the files code
// without loss), whether built in memory, built and written (with their copies of detail 2), read
// from the copies, or read from the files (the copies gone: written again by that reader); and at
// full detail, read from the files, the whole build's lines bit for bit.
TEST(CreaseTiles, LinesComeAtTheirUnitsDetailFromEverySource) {
    const test::TempDir dir;
    const JacksboroNetwork n;
    const DrainageGrid& g = n.g;
    const DrainageResult& res = n.res;
    const SizeTest strict{n.lo, 0.05, 2.0};
    const CreaseTiles::LineDetail detail = [&](glm::vec2, glm::vec2, float) { return 4.5 * g.dx; };  // detail 2
    const DrapedLineSet want_all = thinned_lines(n.db.creases, 4.0 * g.dx);
    const auto expect_detail = [&](CreaseTiles& tiles, const std::string& what) {
        std::vector<std::uint32_t> ids;
        const DrapedLineSet got = tiles.lines_for_box(n.lo, n.hi, &ids, strict.bound(), detail);
        EXPECT_GT(ids.size(), 100u) << what;
        std::size_t bad = 0;
        for (std::uint32_t i = 0; i < ids.size(); ++i) bad += !same_line(got, i, want_all, ids[i]);
        EXPECT_EQ(bad, 0u) << what;
        std::size_t off = 0;  // every vertex on the creases' lattice, which the files code
        VertexCode code;
        for (const DrapedVertex& v : got.vertices) off += !vertex_code(v, crease_lattice(g), code);
        EXPECT_EQ(off, 0u) << what;
        return ids.size();
    };
    CreaseTiles memory(g, res.dir, res.net, 64);
    const std::size_t stems = expect_detail(memory, "in memory");
    const TileStore store{dir.file("tiles"), 42};
    CreaseTiles first(g, res.dir, res.net, 64, store);
    expect_detail(first, "built, with copies");
    const std::size_t full_files = first.tiles_written() / 2;  // each file and its copy
    EXPECT_EQ(first.tiles_written(), 2 * full_files);
    CreaseTiles second(g, res.dir, res.net, 64, store);
    expect_detail(second, "copies read");
    EXPECT_EQ(second.tiles_written(), 0u);
    for (const auto& e : std::filesystem::directory_iterator(store.folder))  // the copies gone: read from the files
        if (e.path().filename().string().find("-d2.pnlt") != std::string::npos) std::filesystem::remove(e.path());
    CreaseTiles again(g, res.dir, res.net, 64, store);
    expect_detail(again, "read, copies written");
    EXPECT_EQ(again.tiles_written(), full_files);  // a copy of each file read
    CreaseTiles third(g, res.dir, res.net, 64, store);
    EXPECT_EQ(expect_detail(third, "copies read"), stems);
    EXPECT_EQ(third.tiles_written(), 0u);
    EXPECT_EQ(third.tiles_read(), full_files);
    std::size_t copies = 0;
    for (const auto& e : std::filesystem::directory_iterator(store.folder))
        copies += e.path().filename().string().find("-d2.pnlt") != std::string::npos;
    EXPECT_EQ(copies, full_files);
    // detail 1 (crease_copy_detail): copies of its own too, thinned from the files and written by
    // the first query at that detail, read by the next
    static_assert(crease_copy_detail == 1);
    const CreaseTiles::LineDetail fine = [&](glm::vec2, glm::vec2, float) { return 2.5 * g.dx; };
    const DrapedLineSet want = thinned_lines(n.db.creases, 2.0 * g.dx);
    std::vector<std::uint32_t> ids;
    std::size_t bad = 0;
    for (int reader = 0; reader < 2; ++reader) {
        CreaseTiles fourth(g, res.dir, res.net, 64, store);
        const DrapedLineSet got = fourth.lines_for_box(n.lo, n.hi, &ids, strict.bound(), fine);
        for (std::uint32_t i = 0; i < ids.size(); ++i) bad += !same_line(got, i, want, ids[i]);
        EXPECT_EQ(bad, 0u) << reader;
        EXPECT_EQ(fourth.tiles_written(), reader == 0 ? full_files : 0u) << reader;
        EXPECT_EQ(fourth.tiles_read(), full_files) << reader;
    }
    copies = 0;
    for (const auto& e : std::filesystem::directory_iterator(store.folder))
        copies += e.path().filename().string().find("-d1.pnlt") != std::string::npos;
    EXPECT_EQ(copies, full_files);
    CreaseTiles fifth(g, res.dir, res.net, 64, store);  // full detail: the files as they are
    const DrapedLineSet full = fifth.lines_for_box(n.lo, n.hi, &ids, strict.bound());
    EXPECT_EQ(fifth.tiles_read(), full_files);
    EXPECT_EQ(fifth.tiles_built(), 0u);
    bad = 0;
    for (std::uint32_t i = 0; i < ids.size(); ++i) bad += !same_line(full, i, n.db.creases, ids[i]);
    EXPECT_EQ(bad, 0u);
    EXPECT_EQ(ids.size(), stems);
}

}  // namespace
}  // namespace penink
