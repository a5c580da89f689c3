// What crease tiles read of a build, coded (crease_source.hpp), decodes to the same grid arrays,
// directions and tile index (the stems' bounds too) bit for bit; the network made again from the directions equals the
// build's; tiles made from the decoded parts give the whole build's creases bit for bit (volcano
// at its automatic factor and geographic jacksboro, 64-cell tiles); bytes cut short, with a byte
// more, or of another grid width do not decode. A network stored with them is filled by blocks
// where the stems' walks reach, to the build's values.
#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"

namespace penink {
namespace {

void expect_round_trip(const Terrain& t, int factor, const std::string& what) {
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    ASSERT_FALSE(db.creases.lines.empty()) << what;
    const CreaseTileIndex index = crease_tile_index(g, res.dir, res.net, 64);
    const std::vector<std::uint8_t> bytes = encode_crease_source(g, res.dir, index);
    ::testing::Test::RecordProperty(what + "_bytes", int(bytes.size()));
    ::testing::Test::RecordProperty(what + "_nodes", int(g.size()));

    DrainageGrid h;
    std::vector<std::uint8_t> dir;
    CreaseTileIndex got;
    ASSERT_TRUE(decode_crease_source(bytes.data(), bytes.size(), h, dir, got)) << what;
    EXPECT_EQ(std::memcmp(h.z.data(), g.z.data(), g.z.size() * sizeof(float)), 0) << what;
    EXPECT_EQ(h.valid, g.valid) << what;
    EXPECT_EQ(h.cols, g.cols) << what;
    EXPECT_EQ(h.rows, g.rows) << what;
    EXPECT_EQ(h.factor, g.factor) << what;
    EXPECT_EQ(h.dx, g.dx) << what;
    EXPECT_EQ(h.dy, g.dy) << what;
    EXPECT_EQ(h.origin, g.origin) << what;
    EXPECT_EQ(h.coarse_cols, g.coarse_cols) << what;
    EXPECT_EQ(h.coarse_rows, g.coarse_rows) << what;
    EXPECT_EQ(h.coarse_xy, g.coarse_xy) << what;
    // (left empty where it is the fine mask: at factor 1, drainage_grid.hpp)
    if (h.factor == 1 && h.coarse_valid.empty()) {
        EXPECT_TRUE(g.coarse_valid.empty() || g.coarse_valid == g.valid) << what;
    } else {
        EXPECT_EQ(h.coarse_valid, g.coarse_valid) << what;
    }
    ASSERT_EQ(h.coarse_z.size(), g.coarse_z.size()) << what;
    if (!g.coarse_z.empty()) {  // bit for bit (NaN heights compare unequal as floats); memcmp of no bytes wants pointers
        EXPECT_EQ(std::memcmp(h.coarse_z.data(), g.coarse_z.data(), g.coarse_z.size() * sizeof(float)), 0) << what;
    }
    EXPECT_EQ(h.has_affine, g.has_affine) << what;
    EXPECT_EQ(h.affine, g.affine) << what;
    EXPECT_EQ(dir, res.dir) << what;
    EXPECT_EQ(got.side, 64) << what;
    EXPECT_EQ(got.parts.sources, index.parts.sources) << what;
    EXPECT_EQ(got.parts.lo, index.parts.lo) << what;
    EXPECT_EQ(got.parts.hi, index.parts.hi) << what;
    EXPECT_EQ(got.lo, index.lo) << what;
    EXPECT_EQ(got.hi, index.hi) << what;
    EXPECT_TRUE(got.stems == index.stems) << what;
    EXPECT_EQ(got.z_top, index.z_top) << what;
    EXPECT_TRUE(got.units == index.units) << what;
    ASSERT_FALSE(index.units.empty()) << what;
    {  // the units summarise the stems: counts add up, every stem's bound inside its unit's
        std::size_t in_units = 0;
        for (const CreaseUnit& u : index.units) in_units += u.count;
        EXPECT_EQ(in_units, index.stems.size()) << what;
        EXPECT_TRUE(crease_units(index, g.cols, g.rows, g.dx) == index.units) << what;
    }

    {  // the index and the grid's scalars alone
        DrainageGrid s;
        std::vector<std::uint8_t> no_dir;
        CreaseTileIndex index_only;
        ASSERT_TRUE(decode_crease_source(bytes.data(), bytes.size(), s, no_dir, index_only, SourcePart::index)) << what;
        EXPECT_EQ(s.cols, g.cols) << what;
        EXPECT_EQ(s.rows, g.rows) << what;
        EXPECT_EQ(s.origin, g.origin) << what;
        EXPECT_TRUE(s.z.empty() && s.valid.empty() && s.coarse_xy.empty() && no_dir.empty()) << what;
        EXPECT_EQ(index_only.lo, index.lo) << what;
        EXPECT_EQ(index_only.parts.sources, index.parts.sources) << what;
        EXPECT_TRUE(index_only.stems == index.stems) << what;
        CreaseTileIndex units;  // the units alone: no sources, no bounds
        ASSERT_TRUE(decode_crease_source(bytes.data(), bytes.size(), s, no_dir, units, SourcePart::units)) << what;
        EXPECT_TRUE(units.units == index.units) << what;
        EXPECT_TRUE(units.parts.sources.empty() && units.stems.empty()) << what;
        EXPECT_EQ(units.parts.lo, index.parts.lo) << what;
        EXPECT_EQ(units.lo, index.lo) << what;
        EXPECT_EQ(units.z_top, index.z_top) << what;
        DrainageGrid arrays;  // the grid and directions with the units alone
        std::vector<std::uint8_t> grid_dir;
        CreaseTileIndex grid_units;
        ASSERT_TRUE(decode_crease_source(bytes.data(), bytes.size(), arrays, grid_dir, grid_units, SourcePart::grid)) << what;
        EXPECT_EQ(grid_dir, res.dir) << what;
        EXPECT_EQ(arrays.valid, g.valid) << what;
        EXPECT_EQ(std::memcmp(arrays.z.data(), g.z.data(), g.z.size() * sizeof(float)), 0) << what;
        EXPECT_TRUE(grid_units.parts.sources.empty() && grid_units.stems.empty()) << what;
        EXPECT_TRUE(grid_units.units == index.units) << what;
    }
    {  // units whose counts the stems do not fit are a builder's fault; units out of order do not decode
        CreaseTileIndex miscounted = index, disordered = index;
        ++miscounted.units[0].count;
        EXPECT_THROW(encode_crease_source(g, res.dir, miscounted), Error) << what;
        ASSERT_GT(index.units.size(), 1u) << what;
        std::swap(disordered.units.front(), disordered.units.back());
        const std::vector<std::uint8_t> b = encode_crease_source(g, res.dir, disordered);
        DrainageGrid s;
        std::vector<std::uint8_t> d;
        CreaseTileIndex i;
        EXPECT_FALSE(decode_crease_source(b.data(), b.size(), s, d, i, SourcePart::units)) << what;
    }
    {  // each unit's block alone gives its stems and their bounds
        DrainageGrid s;
        std::vector<std::uint8_t> d;
        CreaseTileIndex units;
        std::vector<SourceUnitBlock> blocks;
        ASSERT_TRUE(decode_crease_source(bytes.data(), bytes.size(), s, d, units, SourcePart::units, &blocks)) << what;
        ASSERT_EQ(blocks.size(), index.units.size()) << what;
        const std::vector<std::vector<std::uint32_t>> members = crease_unit_stems(index, g.cols, g.rows, g.dx);
        std::size_t bad = 0;
        for (std::size_t u = 0; u < blocks.size(); ++u) {
            std::vector<std::uint32_t> ids;
            std::vector<StemBound> bounds;
            ASSERT_TRUE(decode_crease_unit(CreaseSourceBytes{bytes.data(), bytes.size()}, blocks[u], ids, bounds)) << what;
            bad += ids != members[u];
            for (std::size_t k = 0; k < ids.size() && k < bounds.size(); ++k) bad += !(bounds[k] == index.stems[ids[k]]);
        }
        EXPECT_EQ(bad, 0u) << what;
        std::vector<std::uint32_t> ids;  // a block beyond the bytes given
        std::vector<StemBound> bounds;
        EXPECT_FALSE(decode_crease_unit(CreaseSourceBytes{bytes.data(), blocks[0].at + 2}, blocks[0], ids, bounds)) << what;
        SourceUnitBlock hostile = blocks[0];  // a count its coded ids cannot hold: refused before allocating
        hostile.count = 1u << 31;
        EXPECT_FALSE(decode_crease_unit(CreaseSourceBytes{bytes.data(), bytes.size()}, hostile, ids, bounds)) << what;
        EXPECT_LT(ids.capacity(), std::size_t(1) << 20) << what;
    }

    const FlowNetwork net = network_of_directions(h, dir);
    EXPECT_TRUE(std::equal(net.acc.begin(), net.acc.end(), res.net.acc.begin(), res.net.acc.end())) << what;
    EXPECT_EQ(net.order, res.net.order) << what;
    EXPECT_TRUE(std::equal(net.basin.begin(), net.basin.end(), res.net.basin.begin(), res.net.basin.end())) << what;
    EXPECT_EQ(net.outlet, res.net.outlet) << what;

    CreaseTiles tiles(h, dir, net, got);
    EXPECT_EQ(tiles.tile_count(), index.lo.size()) << what;
    glm::vec2 lo(-1e30f), hi(1e30f);
    std::vector<std::uint32_t> ids;
    const DrapedLineSet all = tiles.lines_for_box(lo, hi, &ids);
    ASSERT_EQ(all.lines.size(), db.creases.lines.size()) << what;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < all.lines.size(); ++i) {
        const DrapedLine &a = all.lines[i], &b = db.creases.lines[ids[i]];
        bad += !(ids[i] == i && std::memcmp(&a.lo, &b.lo, sizeof a.lo) == 0 && std::memcmp(&a.hi, &b.hi, sizeof a.hi) == 0 &&
                 std::memcmp(&a.length, &b.length, sizeof a.length) == 0 && a.count == b.count && a.order == b.order &&
                 std::memcmp(all.vertices.data() + a.first, db.creases.vertices.data() + b.first,
                             sizeof(DrapedVertex) * a.count) == 0);
    }
    EXPECT_EQ(bad, 0u) << what;

    // damaged or foreign bytes
    EXPECT_FALSE(decode_crease_source(bytes.data(), bytes.size() - 1, h, dir, got)) << what;
    EXPECT_FALSE(decode_crease_source(bytes.data(), bytes.size() / 2, h, dir, got)) << what;
    std::vector<std::uint8_t> longer = bytes;
    longer.push_back(0);
    EXPECT_FALSE(decode_crease_source(longer.data(), longer.size(), h, dir, got)) << what;
    std::vector<std::uint8_t> other = bytes;
    other[0] ^= 1;  // another grid width
    EXPECT_FALSE(decode_crease_source(other.data(), other.size(), h, dir, got)) << what;
}

TEST(CreaseSource, DecodesToTheBuildsPartsAndTheSameCreases) {
    const Terrain volcano = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    expect_round_trip(volcano, drainage_resample_factor(volcano, DrainageOptions{}), "volcano_auto");
    expect_round_trip(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 1, "jacksboro_factor1");
}

// A source storing its network (code_source_network) decodes to a network whose mains are the
// build's and whose in-degrees, orders and flows are filled by blocks where walks reach: each
// filled cell's in-degree, order and flow the build's (normalised_flow's floats); crease tiles built on
// it give the whole build's creases bit for bit, a small box's filling a fraction of the blocks;
// a network section with a block side of 0, more basins than cells or cut short does not decode,
// and a block of garbage throws when first reached (and again: it is not marked filled).
// `few`: the box fills under three quarters of the blocks (a grid of many blocks).
void expect_stored_network(const Terrain& t, int factor, const std::string& what, bool few) {
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    ASSERT_FALSE(db.creases.lines.empty()) << what;
    res.net.mains = main_upstream_bits(g, res.dir, res.net);
    const CreaseTileIndex index = crease_tile_index(g, res.dir, res.net, 64);
    const std::vector<std::uint8_t> without = encode_crease_source(g, res.dir, index);
    // blocks of 32 cells: jacksboro (403 x 344) in 13 x 11
    constexpr int side = 32;
    const std::vector<std::uint8_t> bytes = encode_crease_source(g, res.dir, index, nullptr, &res.net, side);
    ::testing::Test::RecordProperty(what + "_network_bytes", int(bytes.size() - without.size()));
    EXPECT_GT(bytes.size(), without.size()) << what;
    // the residuals vanish but at the blocks' edges: 0.24 (volcano) and 0.29 (jacksboro) B a node
    // in blocks of 32 cells, where the values coded as they are took 1.0 and 1.1
    EXPECT_LT(bytes.size() - without.size(), g.size() * 2 / 5) << what;

    DrainageGrid h;
    std::vector<std::uint8_t> dir;
    CreaseTileIndex got;
    FlowNetwork net;
    ASSERT_TRUE(decode_crease_source(CreaseSourceBytes{bytes.data(), bytes.size()}, h, dir, got, SourcePart::all,
                                     nullptr, &net)) << what;
    ASSERT_TRUE(net.blocks) << what;
    EXPECT_TRUE(net.acc.empty() && net.basin.empty() && net.outlet.empty()) << what;
    EXPECT_EQ(net.mains, res.net.mains) << what;
    EXPECT_EQ(net.indeg.size(), g.size()) << what;
    const std::size_t blocks = std::size_t((g.cols + side - 1) / side) * std::size_t((g.rows + side - 1) / side);
    ASSERT_GT(blocks, 1u) << what;
    EXPECT_EQ(net.blocks->filled(), 0u) << what;

    // the creases of a box an eighth of the grid's side: the whole build's lines meeting it, the
    // blocks of the cells walked filled
    CreaseTiles tiles(h, dir, net, got);
    const glm::vec2 mid = (index.parts.lo + index.parts.hi) * 0.5f, half = (index.parts.hi - index.parts.lo) / 16.0f;
    std::vector<std::uint32_t> ids;
    const DrapedLineSet part = tiles.lines_for_box(mid - half, mid + half, &ids);
    ASSERT_FALSE(part.lines.empty()) << what;
    EXPECT_GT(net.blocks->filled(), 0u) << what;
    if (few) {
        EXPECT_LT(net.blocks->filled(), blocks * 3 / 4) << what;  // 68 of 143 on jacksboro
    }
    ::testing::Test::RecordProperty(what + "_blocks_filled_for_box", int(net.blocks->filled()));
    auto same = [&](const DrapedLineSet& set, const std::vector<std::uint32_t>& at) {
        std::size_t bad = 0;
        for (std::size_t i = 0; i < set.lines.size(); ++i) {
            const DrapedLine &a = set.lines[i], &b = db.creases.lines[at[i]];
            bad += !(a.count == b.count && a.order == b.order && std::memcmp(&a.length, &b.length, sizeof a.length) == 0 &&
                     std::memcmp(set.vertices.data() + a.first, db.creases.vertices.data() + b.first,
                                 sizeof(DrapedVertex) * a.count) == 0);
        }
        return bad;
    };
    EXPECT_EQ(same(part, ids), 0u) << what;
    const DrapedLineSet all = tiles.lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f), &ids);
    ASSERT_EQ(all.lines.size(), db.creases.lines.size()) << what;
    EXPECT_EQ(same(all, ids), 0u) << what;

    // hostile network sections: a block side of 0, more basins than cells, bytes cut short in the
    // blocks do not decode; a block whose bytes are garbage throws when a walk first reaches it
    {
        const std::size_t at = without.size() - 4;  // the network's flag, then its side and basins
        auto refused = [&](std::vector<std::uint8_t> b) {
            DrainageGrid hh;
            std::vector<std::uint8_t> dd;
            CreaseTileIndex ii;
            FlowNetwork nn;
            return !decode_crease_source(CreaseSourceBytes{b.data(), b.size()}, hh, dd, ii, SourcePart::grid, nullptr, &nn);
        };
        std::vector<std::uint8_t> b = bytes;
        std::memset(b.data() + at + 4, 0, 4);
        EXPECT_TRUE(refused(b)) << what << ": side 0";
        b = bytes;
        const std::uint64_t basins = g.size() + 1;
        std::memcpy(b.data() + at + 8, &basins, 8);
        EXPECT_TRUE(refused(b)) << what << ": basins";
        b = bytes;
        b.pop_back();
        EXPECT_TRUE(refused(b)) << what << ": cut";
        b = bytes;
        std::memset(b.data() + b.size() - 8, 0xff, 8);  // the last block's last bytes
        DrainageGrid hh;
        std::vector<std::uint8_t> dd;
        CreaseTileIndex ii;
        FlowNetwork nn;
        ASSERT_TRUE(decode_crease_source(CreaseSourceBytes{b.data(), b.size()}, hh, dd, ii, SourcePart::grid, nullptr, &nn))
            << what;
        nn.blocks->need(0);  // the first block: whole
        EXPECT_THROW(nn.blocks->need(g.size() - 1), Error) << what;
        EXPECT_THROW(nn.blocks->need(g.size() - 1), Error) << what << ": again, not marked filled";
        EXPECT_FALSE(decode_crease_source(b.data(), b.size(), hh, dd, ii)) << what << ": a whole decode checks every block";
    }

    // every cell filled: the build's in-degrees, orders and flows
    for (std::size_t i = 0; i < g.size(); ++i) net.blocks->need(i);
    EXPECT_EQ(net.blocks->filled(), blocks) << what;
    EXPECT_EQ(net.indeg, inflow_counts(res.dir, GridShape{g.cols, g.rows, g.valid.data()})) << what;
    EXPECT_EQ(net.order, res.net.order) << what;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < g.size(); ++i)
        bad += std::bit_cast<float>(net.flow[i]) != normalised_flow(res.net, i) || normalised_flow(net, i) != normalised_flow(res.net, i);
    EXPECT_EQ(bad, 0u) << what;
}

TEST(CreaseSource, StoredNetworkFilledByBlocksGivesTheSameCreases) {
    const Terrain volcano = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    expect_stored_network(volcano, drainage_resample_factor(volcano, DrainageOptions{}), "volcano_auto", false);
    expect_stored_network(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 1, "jacksboro_factor1", true);
}

// At factor 1 the coarse mask is the fine one and is stored once; a grid whose coarse mask
// differs (one node) stores it and decodes to it. The arrays coded one by one and assembled give
// encode_crease_source's bytes.
TEST(CreaseSource, CoarseMaskAtFactorOneStoredOnce) {
    DrainageGrid g = resample_pn(read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc"), 1);
    DrainageResult res;
    drainage_db_from_grid(g, {}, &res);
    ASSERT_EQ(g.coarse_valid, g.valid);
    const CreaseTileIndex index = crease_tile_index(g, res.dir, res.net, 64);
    const std::vector<std::uint8_t> shared = encode_crease_source(g, res.dir, index);
    std::vector<CodedSourceArray> arrays;
    for (std::size_t a = 0; a < source_array_count; ++a) arrays.push_back(code_source_array(g, res.dir, SourceArray(a)));
    EXPECT_EQ(arrays[std::size_t(SourceArray::coarse_valid)].elements, 0u);
    EXPECT_EQ(assemble_crease_source(g, code_crease_index(index, g.cols, g.rows, g.dx), arrays), shared);
    // the index made and coded a row of tiles at a time: the same bytes
    EXPECT_EQ(assemble_crease_source(g, coded_crease_tile_index(g, res.dir, res.net, 64), arrays), shared);
    DrainageGrid other = g;
    other.coarse_valid[other.coarse_valid.size() / 2] ^= 1;
    const std::vector<std::uint8_t> own = encode_crease_source(other, res.dir, index);
    EXPECT_GT(own.size(), shared.size());
    for (const auto* grid : {&g, &other}) {
        const std::vector<std::uint8_t>& bytes = grid == &g ? shared : own;
        DrainageGrid h;
        std::vector<std::uint8_t> dir;
        CreaseTileIndex got;
        ASSERT_TRUE(decode_crease_source(bytes.data(), bytes.size(), h, dir, got));
        // the shared mask decoded as none (the fine one), the other as stored
        EXPECT_EQ(h.coarse_valid, grid == &g ? std::vector<std::uint8_t>() : grid->coarse_valid);
        EXPECT_EQ(h.valid, g.valid);
    }
}

// At factor 1 a source referring to its DEM stores neither the heights nor the nodes' UTM x, y
// (geographic jacksboro: a fraction of the bytes) and decodes to the same arrays, read from the
// DEM again; its index decodes without the DEM; a DEM gone or another at its path: no decode.
TEST(CreaseSource, HeightsReadFromTheDemItRefersTo) {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() / ("penink_source_dem_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    const fs::path dem = d / "j.tif";
    fs::copy_file(PENINK_SOURCE_DIR "/examples/jacksboro.tif", dem);
    const Terrain t = read_dem(dem.string());
    ASSERT_TRUE(t.source_geographic);
    DrainageGrid g = resample_pn(t, 1);
    DrainageResult res;
    drainage_db_from_grid(g, {}, &res);
    const CreaseTileIndex index = crease_tile_index(g, res.dir, res.net, 64);
    const DemHeightsRef ref{absolute_dem_path(dem.string()), t.utm_zone, t.north};
    const std::vector<std::uint8_t> stored = encode_crease_source(g, res.dir, index);
    const std::vector<std::uint8_t> referred = encode_crease_source(g, res.dir, index, &ref);
    // The heights and x, y coded take about 1.9 B a node on jacksboro (their deltas deflated); the
    // rest (mask, directions, index, stems' bounds) is the same in both.
    EXPECT_GT(stored.size(), referred.size() + 3 * g.size() / 2) << referred.size() << " vs " << stored.size();
    EXPECT_EQ(crease_source_dem(referred.data(), referred.size()), ref.path);
    EXPECT_EQ(crease_source_dem(stored.data(), stored.size()), "");
    DrainageGrid h;
    std::vector<std::uint8_t> dir;
    CreaseTileIndex got;
    ASSERT_TRUE(decode_crease_source(referred.data(), referred.size(), h, dir, got));
    EXPECT_EQ(std::memcmp(h.z.data(), g.z.data(), g.z.size() * sizeof(float)), 0);
    EXPECT_EQ(h.z.size(), g.z.size());
    EXPECT_EQ(h.coarse_xy, g.coarse_xy);
    EXPECT_EQ(h.valid, g.valid);
    EXPECT_EQ(dir, res.dir);
    EXPECT_EQ(got.parts.sources, index.parts.sources);
    // the grid with the network made beside the DEM opened again: the build's network, the
    // heights read and the x, y made by blocks where asked for, checked by their hashes
    FlowNetwork net;
    ASSERT_TRUE(decode_crease_source(CreaseSourceBytes{referred.data(), referred.size()}, h, dir, got, SourcePart::grid, nullptr, &net));
    ASSERT_TRUE(h.node_blocks);
    EXPECT_EQ(h.node_blocks->filled(), 0u);
    EXPECT_EQ(grid_xy(h, 7, 5), grid_xy(g, 7, 5));
    EXPECT_EQ(h.node_blocks->filled(), 1u);
    EXPECT_EQ(h.z[h.index(7, 5)], g.z[g.index(7, 5)]);
    for (std::size_t i = 0; i < h.size(); ++i) need_node(h, i);
    EXPECT_EQ(h.node_blocks->filled(), h.node_blocks->grid().count());
    EXPECT_EQ(std::memcmp(h.z.data(), g.z.data(), g.z.size() * sizeof(float)), 0);
    EXPECT_EQ(h.coarse_xy, g.coarse_xy);
    EXPECT_TRUE(std::equal(net.acc.begin(), net.acc.end(), res.net.acc.begin(), res.net.acc.end()));
    EXPECT_EQ(net.order, res.net.order);
    EXPECT_TRUE(std::equal(net.basin.begin(), net.basin.end(), res.net.basin.begin(), res.net.basin.end()));
    EXPECT_EQ(net.outlet, res.net.outlet);
    EXPECT_EQ(net.indeg, inflow_counts(res.dir, GridShape{g.cols, g.rows, g.valid.data()}));
    // the heights by blocks too, through NodeHeights (a render's terrain cache; here the build's
    // own), each block's rows read when a node of it is first asked for, checked by its hash
    std::size_t spans = 0;
    const NodeHeights own{g.cols, g.rows, [&](int r, int c0, int c1, float* z) {
                              ++spans;
                              std::memcpy(z, g.z.data() + g.index(c0, r), std::size_t(c1 - c0) * sizeof(float));
                          }};
    DrainageGrid k;
    ASSERT_TRUE(decode_crease_source(CreaseSourceBytes{referred.data(), referred.size()}, k, dir, got, SourcePart::grid,
                                     nullptr, &net, &own));
    ASSERT_TRUE(k.node_blocks);
    EXPECT_EQ(spans, 0u);
    EXPECT_EQ(grid_xy(k, 7, 5), grid_xy(g, 7, 5));
    EXPECT_EQ(spans, 128u);  // the first block's rows
    EXPECT_TRUE(k.z.empty());
    EXPECT_EQ(node_heights(k)[k.index(7, 5)], g.z[g.index(7, 5)]);
    for (std::size_t i = 0; i < k.size(); ++i) need_node(k, i);
    EXPECT_EQ(spans, std::size_t(4 * 344));  // 403 x 344 nodes: 4 blocks a row of blocks, each row once
    EXPECT_EQ(std::memcmp(node_heights(k), g.z.data(), g.z.size() * sizeof(float)), 0);
    EXPECT_EQ(k.coarse_xy, g.coarse_xy);
    // other heights than the build's: refused where first read
    const NodeHeights raised{g.cols, g.rows, [&](int r, int c0, int c1, float* z) {
                                 own.span(r, c0, c1, z);
                                 z[0] += 1.0f;
                             }};
    ASSERT_TRUE(decode_crease_source(CreaseSourceBytes{referred.data(), referred.size()}, k, dir, got, SourcePart::grid,
                                     nullptr, &net, &raised));
    EXPECT_THROW(need_node(k, k.index(7, 5)), Error);
    fs::remove(dem);
    EXPECT_FALSE(decode_crease_source(referred.data(), referred.size(), h, dir, got));  // gone
    EXPECT_TRUE(decode_crease_source(referred.data(), referred.size(), h, dir, got, SourcePart::index));  // the index alone
    EXPECT_EQ(got.lo, index.lo);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dem);  // another DEM at its path
    EXPECT_FALSE(decode_crease_source(referred.data(), referred.size(), h, dir, got));
    fs::remove_all(d);
}

}  // namespace
}  // namespace penink
