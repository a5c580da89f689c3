// Lines built for part of the DEM (draped_lines.hpp: crease_part, ridge_part) equal the whole
// build's line for line, bit for bit: the stems built in tiles of 32 x 32 cells (by the stem's
// source cell) and the divides in runs of 97 ids, the parts in shuffled order, and the divides'
// smoothing on the stems as walked (which join: chains across parts), on volcano at its
// automatic factor and at factor 1, on a DEM with nodata holes at factor 2 and on geographic
// jacksboro's curvilinear grid; the stems the same again with the junctions' mains found first
// (main_upstream_bits: one bit a junction). Many joins cross a part's edge (the closure is what
// makes them equal), and the closure of joins adds each joined line once.
#include <algorithm>
#include <bit>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "line_test_dems.hpp"

#include "drainage/dem_surface.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/fall_line_stems.hpp"
#include "drainage/flow_network.hpp"
#include "drainage/ridge_crests.hpp"
#include "drainage/stems.hpp"

namespace penink {
namespace {

// Mismatching lines of `part` (its line i is the whole set's line ids[i]): records and vertices
// compared bit for bit.
std::size_t mismatches(const DrapedLineSet& whole, const DrapedLineSet& part, const std::vector<std::uint32_t>& ids) {
    std::size_t bad = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const DrapedLine &w = whole.lines[ids[i]], &p = part.lines[i];
        const bool same_record = std::memcmp(&w.lo, &p.lo, sizeof w.lo) == 0 && std::memcmp(&w.hi, &p.hi, sizeof w.hi) == 0 &&
                                 std::memcmp(&w.length, &p.length, sizeof w.length) == 0 && w.count == p.count &&
                                 w.order == p.order;
        const bool same_vertices =
            same_record && std::memcmp(whole.vertices.data() + w.first, part.vertices.data() + p.first,
                                       sizeof(DrapedVertex) * w.count) == 0;
        bad += !same_vertices;
    }
    return bad;
}

// Parts of the ids [0, n) in shuffled order (seeded): `of(id)` names each id's part.
template <class Of> std::vector<std::vector<std::uint32_t>> shuffled_parts(std::size_t n, std::size_t parts, Of&& of) {
    std::vector<std::vector<std::uint32_t>> out(parts);
    for (std::uint32_t id = 0; id < n; ++id) out[of(id)].push_back(id);
    std::mt19937 rng(20261205);
    std::shuffle(out.begin(), out.end(), rng);
    out.erase(std::remove_if(out.begin(), out.end(), [](const auto& p) { return p.empty(); }), out.end());
    return out;
}

// Joins whose joined line lies in another part.
std::size_t crossing_joins(const LineJoins& joins, const std::vector<std::vector<std::uint32_t>>& parts) {
    std::vector<std::size_t> part_of(joins.start.size() - 1);
    for (std::size_t p = 0; p < parts.size(); ++p)
        for (std::uint32_t id : parts[p]) part_of[id] = p;
    std::size_t n = 0;
    for (const LineJoin& j : joins.joins) n += part_of[j.line] != part_of[j.into];
    return n;
}

void expect_parts_equal_whole(const Terrain& t, int factor, const std::string& what) {
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    ASSERT_TRUE(has_relief(g)) << what;
    const DemSurface surface(g);

    // stems: tiles of 32 x 32 cells by their source cell
    const StemParts stems_of = stem_parts(g, res.dir, res.net);
    const std::vector<std::uint32_t>& sources = stems_of.sources;
    ASSERT_EQ(sources.size(), db.creases.lines.size()) << what;
    // the joins the whole set's x, y matching finds (those crossing parts counted below), and its
    // box, which stem_parts makes from the cells
    const LineJoins stem_joins = line_joins(network_stems(g, res.dir, res.net));
    EXPECT_EQ(stems_of.lo, stem_joins.lo) << what;
    EXPECT_EQ(stems_of.hi, stem_joins.hi) << what;
    constexpr std::uint32_t tile = 32;
    const std::uint32_t tiles_x = (std::uint32_t(g.cols) + tile - 1) / tile;
    const std::uint32_t tiles_y = (std::uint32_t(g.rows) + tile - 1) / tile;
    const auto stem_parts = shuffled_parts(sources.size(), std::size_t(tiles_x) * tiles_y, [&](std::uint32_t s) {
        const std::uint32_t c = sources[s] % std::uint32_t(g.cols), r = sources[s] / std::uint32_t(g.cols);
        return (r / tile) * tiles_x + c / tile;
    });
    EXPECT_GE(crossing_joins(stem_joins, stem_parts), sources.size() / 100) << what;  // 1 % of the stems
    std::size_t stems = 0, bad_stems = 0;
    for (const auto& ids : stem_parts) {
        const DrapedLineSet part = crease_part(g, res.dir, res.net, surface, stems_of, ids);
        ASSERT_TRUE(line_set_ok(part)) << what;
        ASSERT_EQ(part.lines.size(), ids.size()) << what;
        bad_stems += mismatches(db.creases, part, ids), stems += ids.size();
    }
    EXPECT_EQ(stems, db.creases.lines.size()) << what;
    EXPECT_EQ(bad_stems, 0u) << what;

    // with the junctions' mains found first (main_upstream_bits, as the streamed build keeps them
    // in the network): one bit for each junction, and the same stems bit for bit
    FlowNetwork with_mains = res.net;
    with_mains.mains = main_upstream_bits(g, res.dir, res.net);
    ASSERT_EQ(with_mains.mains.size(), mains_words(g.size())) << what;
    std::size_t junctions = 0, bits = 0;
    for (std::uint8_t n : inflow_counts(res.dir, GridShape{g.cols, g.rows, g.valid.data()})) junctions += n >= 2;
    for (std::uint64_t w : with_mains.mains) bits += std::size_t(std::popcount(w));
    EXPECT_EQ(bits, junctions) << what;
    EXPECT_GT(junctions, sources.size() / 4) << what;
    std::size_t bad_with_mains = 0;
    for (const auto& ids : stem_parts)
        bad_with_mains += mismatches(db.creases, crease_part(g, res.dir, with_mains, surface, stems_of, ids), ids);
    EXPECT_EQ(bad_with_mains, 0u) << what;

    // the network as a render keeps it for the crease tiles (keep_normalised_flow: each cell's
    // normalised flow instead of its accumulation and basin): the same floats, the same stems
    FlowNetwork flow_only = with_mains;
    keep_normalised_flow(flow_only);
    EXPECT_TRUE(flow_only.acc.empty() && flow_only.basin.empty() && flow_only.outlet.empty()) << what;
    ASSERT_EQ(flow_only.flow.size(), g.size()) << what;
    std::size_t flow_differs = 0;
    for (std::size_t i = 0; i < g.size(); ++i)
        flow_differs += std::bit_cast<std::uint32_t>(normalised_flow(flow_only, i)) !=
                        std::bit_cast<std::uint32_t>(normalised_flow(res.net, i));
    EXPECT_EQ(flow_differs, 0u) << what;
    std::size_t bad_flow_only = 0;
    for (const auto& ids : stem_parts)
        bad_flow_only += mismatches(db.creases, crease_part(g, res.dir, flow_only, surface, stems_of, ids), ids);
    EXPECT_EQ(bad_flow_only, 0u) << what;
    flow_only.mains.clear();  // the junctions' mains found from the flow (a network decoded for a render)
    std::size_t bad_no_mains = 0;
    for (const auto& ids : stem_parts)
        bad_no_mains += mismatches(db.creases, crease_part(g, res.dir, flow_only, surface, stems_of, ids), ids);
    EXPECT_EQ(bad_no_mains, 0u) << what;

    // divides: runs of 97 ids
    const DrapedLineSet listed = listed_lines(db.divide_vertices, divide_polylines(db));
    ASSERT_EQ(listed.lines.size(), db.ridges.lines.size()) << what;
    const LineJoins divide_joins = line_joins(listed);
    const auto divide_parts =
        shuffled_parts(listed.lines.size(), (listed.lines.size() + 96) / 97, [](std::uint32_t d) { return d / 97; });
    // (a divide's ends meet other divides' ends, never their interior: no joins to follow there)
    std::size_t bad_divides = 0;
    for (const auto& ids : divide_parts) {
        const DrapedLineSet part = ridge_part(g, surface, listed, divide_joins, ids);
        ASSERT_TRUE(line_set_ok(part)) << what;
        ASSERT_EQ(part.lines.size(), ids.size()) << what;
        bad_divides += mismatches(db.ridges, part, ids);
    }
    EXPECT_EQ(bad_divides, 0u) << what;

    // The divides' smoothing on lines that do join (the stems as walked, before tracing: each
    // ending on its trunk's interior, in chains of joins across parts): ridge_part's closure of
    // four joins against the whole set smoothed (smooth_lines), moved onto crests and draped.
    const DrapedLineSet walked = network_stems(g, res.dir, res.net);
    DrapedLineSet whole = walked;
    smooth_lines(whole, 3.0 * fall_line_options(g).sigma);
    snap_to_crests(whole, surface, crest_options(g));
    drape_lines(whole, surface);
    std::size_t bad_joined = 0;
    for (const auto& ids : stem_parts) {
        const DrapedLineSet part = ridge_part(g, surface, walked, stem_joins, ids);
        ASSERT_EQ(part.lines.size(), ids.size()) << what;
        bad_joined += mismatches(whole, part, ids);
    }
    EXPECT_EQ(bad_joined, 0u) << what;
}

TEST(LineParts, StemsAndDividesBuiltByPartsEqualTheWholeBuild) {
    for (const LineTestDem& dem : line_test_dems()) expect_parts_equal_whole(dem.terrain, dem.factor, dem.name);
}

// The closure adds every line reachable within `depth` joins, once, after the asked ones.
TEST(LineParts, JoinClosureFollowsJoinsToItsDepthOnce) {
    LineJoins j;
    // 0 -> 1 -> 2 -> 3, 4 -> 1, 5 alone
    j.joins = {{0, 1, 1, 3}, {1, 1, 2, 5}, {2, 0, 3, 1}, {2, 1, 3, 2}, {4, 1, 1, 2}};
    j.start = {0, 1, 2, 4, 4, 5, 5};
    EXPECT_EQ(join_closure(j, {0}, 0), (std::vector<std::uint32_t>{0}));
    EXPECT_EQ(join_closure(j, {0}, 1), (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(join_closure(j, {0}, 4), (std::vector<std::uint32_t>{0, 1, 2, 3}));
    EXPECT_EQ(join_closure(j, {4, 0}, 2), (std::vector<std::uint32_t>{4, 0, 1, 2}));
    EXPECT_EQ(join_closure(j, {5, 2}, 4), (std::vector<std::uint32_t>{5, 2, 3}));
}

}  // namespace
}  // namespace penink
