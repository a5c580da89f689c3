// drainage_stems on a hand-made branch tree (branch layout of drainage/branches.hpp: a branch
// ending at a junction repeats the junction as its last vertex, the downstream branch starts
// there). The main stem continues the upstream branch of highest order, then of largest flow
// just above the junction; every vertex appears once, junction positions once per joining stem.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "drainage/stems.hpp"

using namespace penink;

namespace {

struct BranchSpec {
    std::vector<std::pair<float, float>> xy;  // vertex positions
    std::vector<float> flow;                  // per vertex
    std::uint8_t order;
    std::int32_t downstream;
};

// Builds vertices, branches and upstream lists (upstream ids in branch order, as build_branches fills them).
DrainageDb make_db(const std::vector<BranchSpec>& spec) {
    DrainageDb db;
    for (const BranchSpec& s : spec) {
        DvBranch b{};
        b.first = std::uint32_t(db.vertices.size());
        b.count = std::uint32_t(s.xy.size());
        b.order = s.order, b.downstream = s.downstream, b.basin = 1;
        for (std::size_t k = 0; k < s.xy.size(); ++k)
            db.vertices.push_back({s.xy[k].first, s.xy[k].second, 10.0f, s.flow[k]});
        db.branches.push_back(b);
    }
    for (std::size_t d = 0; d < db.branches.size(); ++d) {
        db.branches[d].up_first = std::uint32_t(db.upstream.size());
        for (std::size_t b = 0; b < db.branches.size(); ++b)
            if (db.branches[b].downstream == std::int32_t(d)) db.upstream.push_back(std::uint32_t(b));
        db.branches[d].up_count = std::uint32_t(db.upstream.size()) - db.branches[d].up_first;
    }
    return db;
}

// Sources A (0) and B (1) join at J1 = (5, 0) into C (2); D (3) joins C at J2 = (5, -3) into E (4).
// A and B are both order 1; B carries more flow just above J1, so B continues as C. D carries
// more flow than C above J2 but C has the higher order, so C continues as E. The junction
// vertices hold the junction's own flow (equal for every branch that ends there).
DrainageDb tree() {
    return make_db({
        {{{0, 2}, {1, 1}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}, {0.02f, 0.04f, 0.06f, 0.08f, 0.10f, 0.40f}, 1, 2},  // A
        {{{9, 2}, {8, 1}, {7, 1}, {6, 0}, {5, 0}}, {0.05f, 0.10f, 0.20f, 0.28f, 0.40f}, 1, 2},              // B
        {{{5, 0}, {5, -1}, {5, -2}, {5, -3}}, {0.40f, 0.42f, 0.44f, 0.95f}, 2, 4},                          // C
        {{{0, -5}, {1, -5}, {2, -5}, {3, -4}, {4, -3}, {5, -3}}, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.95f}, 1, 4},  // D
        {{{5, -3}, {5, -4}, {5, -5}}, {0.95f, 0.97f, 1.0f}, 2, -1},                                         // E
    });
}

std::vector<std::uint32_t> range(std::uint32_t first, std::uint32_t last) {  // [first, last]
    std::vector<std::uint32_t> v;
    for (std::uint32_t i = first; i <= last; ++i) v.push_back(i);
    return v;
}

}  // namespace

TEST(DrainageStems, MainStemFollowsOrderThenFlow) {
    const DrainageDb db = tree();
    const auto stems = drainage_stems(db);
    // Vertex ids: A 0-5, B 6-10, C 11-14, D 15-20, E 21-23.
    ASSERT_EQ(stems.size(), 3u);  // one per source, sources in branch order
    EXPECT_EQ(stems[0], range(0, 5));  // A: a tributary, ends at J1 (its vertex 5)
    std::vector<std::uint32_t> main = range(6, 10);  // B, then C without its J1 copy, E without J2
    for (std::uint32_t i : range(12, 14)) main.push_back(i);
    for (std::uint32_t i : range(22, 23)) main.push_back(i);
    EXPECT_EQ(stems[1], main);
    EXPECT_EQ(stems[2], range(15, 20));  // D ends at J2
}

TEST(DrainageStems, EveryVertexOnceJunctionsOncePerJoiningStem) {
    const DrainageDb db = tree();
    const auto stems = drainage_stems(db);
    std::map<std::uint32_t, int> seen;
    std::map<std::pair<float, float>, int> at;
    for (const auto& s : stems)
        for (std::uint32_t i : s) ++seen[i], ++at[{db.vertices[i].x, db.vertices[i].y}];
    for (const auto& [i, n] : seen) EXPECT_EQ(n, 1) << "vertex " << i;
    // All vertices but the junction copies heading C (11) and E (21) are drawn.
    EXPECT_EQ(seen.size(), db.vertices.size() - 2);
    EXPECT_EQ(seen.count(11), 0u);
    EXPECT_EQ(seen.count(21), 0u);
    EXPECT_EQ((at[{5.0f, 0.0f}]), 2);   // J1: end of A, and inside the main stem
    EXPECT_EQ((at[{5.0f, -3.0f}]), 2);  // J2: end of D, and inside the main stem
    for (const auto& [p, n] : at)
        if (p != std::pair{5.0f, 0.0f} && p != std::pair{5.0f, -3.0f}) {
            EXPECT_EQ(n, 1);
        }
    // Consecutive stem vertices are grid neighbours (no jump across the network).
    for (const auto& s : stems)
        for (std::size_t k = 1; k < s.size(); ++k) {
            const DvVertex &a = db.vertices[s[k - 1]], &b = db.vertices[s[k]];
            EXPECT_LE(std::max(std::abs(a.x - b.x), std::abs(a.y - b.y)), 1.0f) << s[k];
        }
}

TEST(DrainageStems, HigherFlowWinsRegardlessOfBranchIndex) {
    // Same tree with A carrying more than B just above J1: now A continues as C.
    DrainageDb db = tree();
    db.vertices[4].flow = 0.35f, db.vertices[9].flow = 0.12f;
    const auto stems = drainage_stems(db);
    ASSERT_EQ(stems.size(), 3u);
    EXPECT_EQ(stems[0].size(), 6u + 3u + 2u);  // A + C + E
    EXPECT_EQ(stems[0].front(), 0u);
    EXPECT_EQ(stems[0].back(), 23u);
    EXPECT_EQ(stems[1], range(6, 10));  // B now ends at J1
}

TEST(DrainageStems, OrderBeatsFlowAndSingleBranches) {
    // An order-2 branch with little flow still beats an order-1 branch with more.
    DrainageDb db = tree();
    for (std::uint32_t i = 15; i < 20; ++i) db.vertices[i].flow = 0.9f;  // D above J2
    auto stems = drainage_stems(db);
    ASSERT_EQ(stems.size(), 3u);
    EXPECT_EQ(stems[2], range(15, 20));
    EXPECT_EQ(stems[1].back(), 23u);
    // A single outlet branch is one stem; an empty database has none.
    const DrainageDb one = make_db({{{{0, 0}, {1, 0}, {2, 1}}, {0.3f, 0.6f, 1.0f}, 1, -1}});
    stems = drainage_stems(one);
    ASSERT_EQ(stems.size(), 1u);
    EXPECT_EQ(stems[0], range(0, 2));
    EXPECT_TRUE(drainage_stems(DrainageDb{}).empty());
}
