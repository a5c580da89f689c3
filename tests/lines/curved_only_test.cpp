// curved_only: a segment whose two edge keys ((a << 32) | b, lower vertex first) name four
// vertices with the same normal (every normal within 1e-3 of the first, by length of the
// difference) lies in a flat fan and is dropped; any differing normal keeps it; a segment with
// an end off the mesh edges (key ~0) is kept without looking at normals. Order is preserved.
// Each segment's strength is used as its id.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "lines/photic_extremum_lines.hpp"

using namespace penink;

namespace {

constexpr std::uint64_t no_edge = ~std::uint64_t(0);

std::uint64_t key(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; }

ObjectSegment segment(float id, std::uint64_t edge_a, std::uint64_t edge_b) {
    ObjectSegment s;
    s.a = {id, 0.0f, 0.0f};
    s.b = {id, 1.0f, 0.0f};
    s.strength = id;
    s.edge_a = edge_a;
    s.edge_b = edge_b;
    return s;
}

std::vector<float> ids(const std::vector<ObjectSegment>& segments) {
    std::vector<float> out;
    for (const ObjectSegment& s : segments) out.push_back(s.strength);
    return out;
}

// Vertices 0-3: +z; 4: tilted 36.9 degrees (differs by 0.63); 5: tilted so its difference from
// +z is ~5e-4 (half the 1e-3 tolerance: "equal"); 6: ~2e-3 (twice the tolerance: "differs").
// Both margins are a factor 2 from the threshold, far above float rounding (~1e-7).
std::vector<glm::vec3> normals() {
    return {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1},
            {0, 0.6f, 0.8f}, glm::normalize(glm::vec3(0, 5e-4f, 1)), glm::normalize(glm::vec3(0, 2e-3f, 1))};
}

}  // namespace

TEST(CurvedOnly, FlatFanSegmentsAreDroppedCurvedOnesKept) {
    const std::vector<glm::vec3> n = normals();
    ASSERT_LT(glm::length(n[5] - n[0]), 1e-3f);
    ASSERT_GT(glm::length(n[6] - n[0]), 1e-3f);
    const std::vector<ObjectSegment> in = {
        segment(1, key(0, 1), key(1, 2)),  // all +z: dropped
        segment(2, key(0, 1), key(2, 4)),  // last of the four vertices differs: kept
        segment(3, key(4, 0), key(1, 2)),  // first differs (the one the others are compared to): kept
        segment(4, key(0, 5), key(2, 3)),  // 5e-4 off: within tolerance, dropped
        segment(5, key(0, 6), key(2, 3)),  // 2e-3 off: kept
        segment(6, key(2, 3), key(0, 3)),  // all +z, shared vertex: dropped
        segment(7, key(1, 2), key(3, 5)),  // 5e-4 off, in edge_b: dropped
    };
    EXPECT_EQ(ids(curved_only(in, n)), (std::vector<float>{2, 3, 5}));
}

TEST(CurvedOnly, DifferenceInTheLowHalfOfEachKeyCounts) {
    // The differing vertex 4 as the low half (b) of edge_a, then of edge_b.
    const std::vector<glm::vec3> n = normals();
    const std::vector<ObjectSegment> in = {segment(1, key(0, 4), key(1, 2)), segment(2, key(1, 2), key(0, 4)),
                                           segment(3, key(4, 0), key(1, 2)), segment(4, key(1, 2), key(4, 0))};
    EXPECT_EQ(ids(curved_only(in, n)), (std::vector<float>{1, 2, 3, 4}));
}

TEST(CurvedOnly, KeylessSegmentsAreKept) {
    // Normals all equal, so only the missing key can keep a segment; with an empty normal list a
    // keyless segment must not index it at all.
    const std::vector<glm::vec3> n = normals();
    const std::vector<ObjectSegment> in = {
        segment(1, no_edge, key(0, 1)),
        segment(2, key(0, 1), no_edge),
        segment(3, no_edge, no_edge),
        segment(4, key(0, 1), key(2, 3)),  // keyed and flat: dropped
    };
    EXPECT_EQ(ids(curved_only(in, n)), (std::vector<float>{1, 2, 3}));
    EXPECT_EQ(ids(curved_only({segment(5, no_edge, no_edge)}, {})), (std::vector<float>{5}));
    EXPECT_TRUE(curved_only({}, n).empty());
}

TEST(CurvedOnly, KeptSegmentsAreUnchanged) {
    const std::vector<glm::vec3> n = normals();
    ObjectSegment s = segment(9, key(0, 4), key(2, 3));
    s.a = {1.5f, -2.0f, 3.25f};
    s.b = {4.0f, 5.5f, -6.0f};
    const std::vector<ObjectSegment> out = curved_only({s}, n);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].a, s.a);
    EXPECT_EQ(out[0].b, s.b);
    EXPECT_EQ(out[0].strength, s.strength);
    EXPECT_EQ(out[0].edge_a, s.edge_a);
    EXPECT_EQ(out[0].edge_b, s.edge_b);
}
