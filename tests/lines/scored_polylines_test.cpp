// scored_runs_to_strokes: runs split at negative scores, at hidden vertices (dm_hidden) and at
// vertices behind the eye; strength = mean score of the kept run; pixels and eye distances from a
// straight-down camera whose projection is known in closed form.
#include <cmath>

#include <gtest/gtest.h>

#include "lines/scored_polylines.hpp"

using namespace penink;

namespace {

constexpr float hidden = -1.0e30f;  // render/dm.hpp's dm_hidden

// Eye 100 m above the origin looking straight down, fov 90 degrees, 200x200 pixels: ground point
// (x, y, 0) lands on pixel (100 + x, 100 - y) (north up), at eye distance sqrt(x^2 + y^2 + 100^2).
Camera down_camera() {
    Camera cam;
    cam.eye = {0.0, 0.0, 100.0};
    cam.azimuth = 0.0, cam.altitude = -90.0, cam.fov = 90.0;
    cam.width = 200, cam.height = 200;
    cam.near_plane = 1.0, cam.far_plane = 1000.0;
    return cam;
}

std::vector<glm::vec3> row_of_points(int n) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < n; ++i) p.emplace_back(float(-50 + 10 * i), float(20 - 3 * i), 0.0f);
    return p;
}

}  // namespace

TEST(ScoredPolylines, PixelsDepthAndStrengthOfOneRun) {
    const std::vector<glm::vec3> p = row_of_points(4);
    const std::vector<float> scores = {0.1f, 0.2f, 0.3f, 0.6f};
    const auto strokes = scored_runs_to_strokes(p, scores, {{0, 4}}, down_camera(), "crease");
    ASSERT_EQ(strokes.size(), 1u);
    const Stroke& s = strokes[0];
    EXPECT_EQ(s.kind, "crease");
    EXPECT_NEAR(s.strength, 0.3f, 1e-6);
    ASSERT_EQ(s.points.size(), 4u);
    ASSERT_EQ(s.depth.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(s.points[i].x, 100.0 + p[i].x, 1e-3) << i;
        EXPECT_NEAR(s.points[i].y, 100.0 - p[i].y, 1e-3) << i;
        EXPECT_NEAR(s.depth[i], std::sqrt(p[i].x * p[i].x + p[i].y * p[i].y + 1e4), 1e-3) << i;
    }
}

TEST(ScoredPolylines, RunsSplitAtNegativeAndHiddenScores) {
    const std::vector<glm::vec3> p = row_of_points(10);
    //                               0     1     2      3     4     5       6     7     8      9
    const std::vector<float> scores = {0.2f, 0.4f, -0.01f, 0.5f, 0.5f, hidden, 0.3f, 0.0f, -0.5f, 0.9f};
    const auto strokes = scored_runs_to_strokes(p, scores, {{0, 10}}, down_camera(), "ridge");
    // Kept: [0, 1], [3, 4], [6, 7] (score 0 is drawn: rs >= 0); [9] alone is too short.
    ASSERT_EQ(strokes.size(), 3u);
    const int first[] = {0, 3, 6};
    const float strength[] = {0.3f, 0.5f, 0.15f};
    for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(strokes[k].points.size(), 2u) << k;
        EXPECT_NEAR(strokes[k].points[0].x, 100.0 + p[first[k]].x, 1e-3) << k;
        EXPECT_NEAR(strokes[k].points[1].x, 100.0 + p[first[k] + 1].x, 1e-3) << k;
        EXPECT_NEAR(strokes[k].strength, strength[k], 1e-6) << k;
        EXPECT_EQ(strokes[k].kind, "ridge");
    }
}

TEST(ScoredPolylines, RunsAreSeparatePolylines) {
    const std::vector<glm::vec3> p = row_of_points(7);
    const std::vector<float> scores(7, 0.25f);
    // Two runs [0, 3) and [3, 7), plus an empty and a one-vertex run: never joined across runs.
    const auto strokes = scored_runs_to_strokes(p, scores, {{0, 3}, {3, 0}, {3, 4}, {6, 1}}, down_camera(), "crease");
    ASSERT_EQ(strokes.size(), 2u);
    EXPECT_EQ(strokes[0].points.size(), 3u);
    EXPECT_EQ(strokes[1].points.size(), 4u);
    EXPECT_NEAR(strokes[1].points[0].x, 100.0 + p[3].x, 1e-3);
    EXPECT_NEAR(strokes[1].points[3].y, 100.0 - p[6].y, 1e-3);
}

TEST(ScoredPolylines, VerticesBehindTheEyeSplitTheRun) {
    std::vector<glm::vec3> p = row_of_points(6);
    p[2].z = 150.0f;  // above the eye, which looks down: behind it
    const std::vector<float> scores(6, 1.0f);
    const auto strokes = scored_runs_to_strokes(p, scores, {{0, 6}}, down_camera(), "crease");
    ASSERT_EQ(strokes.size(), 2u);
    EXPECT_EQ(strokes[0].points.size(), 2u);
    EXPECT_EQ(strokes[1].points.size(), 3u);
    EXPECT_NEAR(strokes[1].points[0].x, 100.0 + p[3].x, 1e-3);
}

// Far creases whole or not at all: a run along x away from the eye whose score, less the
// attenuation, hovers about 0 (dashes) is drawn whole when most of it passes, dropped when most
// of it fails; a run the attenuation does not cut and hidden vertices are left alone.
TEST(ScoredPolylines, DistanceAttenuationDrawsRunsWholeOrNotAtAll) {
    std::vector<glm::vec3> pos;
    for (int i = 0; i < 20; ++i) pos.push_back({float(1000 + 10 * i), 0.0f, 0.0f});
    Camera eye;  // at the origin: depth = x
    const double per_metre = 1e-4;  // 0.1 at 1000 m
    const std::vector<VertexRun> runs{{0, 20}};
    auto scores_with = [&](auto base) {  // score = base(i) - attenuation
        std::vector<float> s;
        for (int i = 0; i < 20; ++i) s.push_back(float(base(i) - per_metre * pos[std::size_t(i)].x));
        return s;
    };
    // every 4th vertex falls under the threshold only through the attenuation: drawn whole
    std::vector<float> s = scores_with([](int i) { return i % 4 == 0 ? 0.05 : 0.5; });
    whole_or_nothing_by_distance(s, pos, runs, eye, per_metre);
    for (float v : s) EXPECT_GE(v, 0.0f);
    // only every 4th vertex passes with the attenuation: none of it
    s = scores_with([](int i) { return i % 4 == 0 ? 0.5 : 0.05; });
    whole_or_nothing_by_distance(s, pos, runs, eye, per_metre);
    for (float v : s) EXPECT_LT(v, 0.0f);
    // not cut by the attenuation (what fails, fails without it too): as it was
    s = scores_with([](int i) { return i < 10 ? 0.5 : -0.01; });
    const std::vector<float> before = s;
    whole_or_nothing_by_distance(s, pos, runs, eye, per_metre);
    EXPECT_EQ(s, before);
    // hidden vertices stay hidden
    s = scores_with([](int i) { return i % 4 == 0 ? 0.05 : 0.5; });
    s[5] = -1.0e30f;
    whole_or_nothing_by_distance(s, pos, runs, eye, per_metre);
    EXPECT_EQ(s[5], -1.0e30f);
    EXPECT_GE(s[4], 0.0f);
}

// A line that leaves the view is drawn to the frame: where the next vertex is hidden and outside
// the frustum, the stroke ends where the segment to it crosses the image border (the down camera
// sees x in [-100, 100] m at the ground: pixel 0 and 200). A hidden neighbour inside the frame
// (occluded) and a low score outside it end the stroke at the last drawn vertex.
TEST(ScoredPolylines, StrokesReachTheFrameWhereTheLineLeavesTheView) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < 11; ++i) p.emplace_back(float(-150 + 30 * i), 10.0f, 0.0f);  // x = -150 ... 150
    std::vector<float> scores(p.size(), 0.5f);
    for (std::size_t i = 0; i < p.size(); ++i)
        if (std::abs(p[i].x) > 100.0f) scores[i] = hidden;  // the DM pass hides what is outside the frustum
    auto strokes = scored_runs_to_strokes(p, scores, {{0, 11}}, down_camera(), "crease");
    ASSERT_EQ(strokes.size(), 1u);
    ASSERT_EQ(strokes[0].points.size(), 7u + 2u);  // x = -90 ... 90, and the two border points
    EXPECT_NEAR(strokes[0].points.front().x, 0.0, 1e-3);
    EXPECT_NEAR(strokes[0].points.back().x, 200.0, 1e-3);
    EXPECT_NEAR(strokes[0].points.back().y, 90.0, 1e-3);
    EXPECT_NEAR(strokes[0].depth.back(), std::sqrt(100.0 * 100.0 + 10.0 * 10.0 + 1e4), 1e-2);
    // the vertex after x = 90 hidden inside the frame instead (x = 95: occluded), the one before
    // x = -90 only scoring low: no border points
    p[9].x = 95.0f;
    scores[1] = -0.2f, scores[2] = 0.5f;
    p[2].x = -95.0f;
    strokes = scored_runs_to_strokes(p, scores, {{0, 11}}, down_camera(), "crease");
    ASSERT_EQ(strokes.size(), 1u);
    EXPECT_NEAR(strokes[0].points.front().x, 100.0 + p[2].x, 1e-3);
    EXPECT_NEAR(strokes[0].points.back().x, 100.0 + p[8].x, 1e-3);
}

TEST(ScoredPolylines, FrustumExitOfASegment) {
    const Camera cam = down_camera();
    const glm::dmat4 vp = view_projection(cam);
    const glm::vec3 e = frustum_exit({0.0f, 0.0f, 0.0f}, {0.0f, 300.0f, 0.0f}, vp);  // north, out at y = 100
    EXPECT_NEAR(e.y, 100.0f, 1e-3);
    const glm::vec3 up = frustum_exit({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 200.0f}, vp);  // up past the eye: near plane
    EXPECT_NEAR(up.z, 99.0f, 1e-3);
    const glm::vec3 same = frustum_exit({0.0f, 0.0f, 0.0f}, {10.0f, 0.0f, 0.0f}, vp);  // both inside
    EXPECT_NEAR(same.x, 10.0f, 1e-6);
}

// Many runs (more than one chunk of the cores' share): the strokes and the whole-or-nothing
// scores are what each run gives alone, in run order.
TEST(ScoredPolylines, ManyRunsGiveEachRunsOwnStrokesInOrder) {
    std::vector<glm::vec3> pos;
    std::vector<float> scores;
    std::vector<VertexRun> runs;
    for (int r = 0; r < 9000; ++r) {
        runs.push_back({std::uint32_t(pos.size()), std::uint32_t(3 + r % 5)});
        for (int i = 0; i < 3 + r % 5; ++i) {
            pos.push_back({float(-80 + (r * 7 + i * 13) % 160), float(-60 + (r * 11 + i * 3) % 120), float(r % 9)});
            const int k = (r * 31 + i * 17) % 23;
            scores.push_back(k == 0 ? hidden : float(k - 4) * 0.05f);  // some negative, some hidden
        }
    }
    const Camera cam = down_camera();
    std::vector<Stroke> alone;
    std::vector<float> whole_alone = scores;
    for (const VertexRun& run : runs) {
        for (Stroke& s : scored_runs_to_strokes(pos, scores, {run}, cam, "crease")) alone.push_back(std::move(s));
        whole_or_nothing_by_distance(whole_alone, pos, {run}, cam, 1e-3);
    }
    const std::vector<Stroke> all = scored_runs_to_strokes(pos, scores, runs, cam, "crease");
    ASSERT_GT(all.size(), 4096u);
    ASSERT_EQ(all.size(), alone.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        ASSERT_EQ(all[i].points, alone[i].points) << i;
        ASSERT_EQ(all[i].depth, alone[i].depth) << i;
        ASSERT_EQ(all[i].strength, alone[i].strength) << i;
    }
    std::vector<float> whole = scores;
    whole_or_nothing_by_distance(whole, pos, runs, cam, 1e-3);
    EXPECT_EQ(whole, whole_alone);
    EXPECT_NE(whole, scores);  // the attenuation cut some runs
}
