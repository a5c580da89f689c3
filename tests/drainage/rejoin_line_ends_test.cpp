// rejoin_line_ends: after smooth_runs_xy, a line end that sat (bit-identical x, y, before
// smoothing) on an interior vertex of a run follows that vertex in x, y; its z stays. Ends that
// match nothing, or only another line's end, stay where they are.
// Coordinates are small integers and halves, so one smoothing pass is exact in float:
// p_k <- (p_k + (p_{k-1} + p_{k+1}) / 2) / 2, and followed ends are copies (compared with ==).
#include <gtest/gtest.h>

#include <vector>

#include "drainage/polyline_smoothing.hpp"

using namespace penink;

namespace {

// Main stem (run 0, vertices 0-4) with a bend at its middle vertex 2 = (20, 10); a tributary
// (run 1, vertices 5-7) from (20, 40) down to the stem's middle vertex, at another z.
std::vector<glm::vec3> stem_and_tributary() {
    return {{0, 0, 10}, {10, 0, 11}, {20, 10, 12}, {30, 0, 13}, {40, 0, 14},
            {20, 40, 30}, {20, 25, 25}, {20, 10, 20}};
}

const std::vector<VertexRun> stem_runs = {{0, 5}, {5, 3}};

}  // namespace

TEST(RejoinLineEnds, TributaryEndFollowsTheStemsMiddleVertex) {
    std::vector<glm::vec3> p = stem_and_tributary();
    const std::vector<glm::vec3> before = p;
    smooth_runs_xy(p, stem_runs, 1);
    // Middle vertex: neighbours' mean (20, 0), halfway from (20, 10): (20, 5).
    ASSERT_EQ(p[2], glm::vec3(20, 5, 12));
    EXPECT_EQ(p[7], before[7]);  // smoothing keeps the tributary's ends
    rejoin_line_ends(before, stem_runs, p);
    EXPECT_EQ(p[7].x, p[2].x);
    EXPECT_EQ(p[7].y, p[2].y);
    EXPECT_EQ(p[7].z, 20.0f);  // its own z, not the stem's 12
    // The tributary's head (20, 40) matches nothing; the stem's ends match nothing either.
    EXPECT_EQ(p[5], before[5]);
    EXPECT_EQ(p[0], before[0]);
    EXPECT_EQ(p[4], before[4]);
    // Interior vertices keep their smoothed positions.
    EXPECT_EQ(p[1], glm::vec3(10, 2.5f, 11));
    EXPECT_EQ(p[3], glm::vec3(30, 2.5f, 13));
    EXPECT_EQ(p[6], glm::vec3(20, 25, 25));
}

TEST(RejoinLineEnds, FollowsAfterManySmoothingPasses) {
    std::vector<glm::vec3> p = stem_and_tributary();
    const std::vector<glm::vec3> before = p;
    smooth_runs_xy(p, stem_runs, 7);
    rejoin_line_ends(before, stem_runs, p);
    EXPECT_NE(p[2].y, 10.0f);  // the junction moved
    EXPECT_EQ(p[7].x, p[2].x);
    EXPECT_EQ(p[7].y, p[2].y);
    EXPECT_EQ(p[7].z, 20.0f);
}

TEST(RejoinLineEnds, BothEndsOfAShortLineFollow) {
    // A two-vertex connector between the stem's vertices 1 and 3 (both interior): both its ends
    // follow; the connector itself is too short to smooth.
    std::vector<glm::vec3> p = stem_and_tributary();
    p.push_back({10, 0, 40});
    p.push_back({30, 0, 41});
    const std::vector<VertexRun> runs = {{0, 5}, {5, 3}, {8, 2}};
    const std::vector<glm::vec3> before = p;
    smooth_runs_xy(p, runs, 1);
    rejoin_line_ends(before, runs, p);
    EXPECT_EQ(p[8], glm::vec3(p[1].x, p[1].y, 40));
    EXPECT_EQ(p[9], glm::vec3(p[3].x, p[3].y, 41));
    EXPECT_EQ(p[8], glm::vec3(10, 2.5f, 40));
}

TEST(RejoinLineEnds, EndOnAnotherLinesEndDoesNotMove) {
    // Line A (vertices 0-2) ends at (40, 0); line B (vertices 3-5) starts there. Ends are not
    // interior vertices, so nothing is rejoined, even when A's end has moved (set by hand here:
    // smoothing never moves ends, so this shows rejoin does not copy from ends).
    std::vector<glm::vec3> p = {{0, 0, 1}, {20, 10, 2}, {40, 0, 3}, {40, 0, 4}, {50, 10, 5}, {60, 0, 6}};
    const std::vector<VertexRun> runs = {{0, 3}, {3, 3}};
    const std::vector<glm::vec3> before = p;
    smooth_runs_xy(p, runs, 1);
    p[2] = {41, 1, 3};
    const std::vector<glm::vec3> smoothed = p;
    rejoin_line_ends(before, runs, p);
    EXPECT_EQ(p, smoothed);
    EXPECT_EQ(p[3], glm::vec3(40, 0, 4));
}

TEST(RejoinLineEnds, MatchIsOnBitIdenticalXYOnly) {
    // A tributary ending 1e-3 beside the junction (20, 10) does not match (the first test's
    // tributary, at the junction's x, y but another z, does: z plays no part in the match).
    std::vector<glm::vec3> p = stem_and_tributary();
    p[7].x = 20.001f;
    const std::vector<glm::vec3> before = p;
    smooth_runs_xy(p, stem_runs, 1);
    rejoin_line_ends(before, stem_runs, p);
    EXPECT_EQ(p[7], before[7]);
}
