// Depth-edge placement of traced silhouette points on hand-made TFT/AFT images: an occluder whose
// edge runs along a pixel row moves its points half a pixel onto the row border, a diagonal edge
// 0.71 px along the diagonal, and points without a farther neighbour (or without an away
// fragment behind them) stay.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "lines/depth_edge_placement.hpp"

using namespace penink;

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

DepthImage image(int w, int h, float value) {
    DepthImage d;
    d.width = w, d.height = h;
    d.depth.assign(std::size_t(w) * h, value);
    return d;
}

float& at(DepthImage& d, int x, int y) { return d.depth[std::size_t(y) * d.width + x]; }

Stroke stroke(std::vector<glm::vec2> points) {
    Stroke s;
    s.points = std::move(points);
    s.depth.assign(s.points.size(), 10.0f);
    return s;
}

}  // namespace

TEST(DepthEdgePlacement, RowEdgeMovesHalfAPixelTowardsTheFarSide) {
    DepthImage toward = image(10, 10, 100.0f), away = image(10, 10, inf);
    for (int y = 0; y <= 4; ++y)
        for (int x = 0; x < 10; ++x) at(toward, x, y) = 10.0f, at(away, x, y) = 20.0f;  // occluder rows 0-4
    std::vector<Stroke> s = {stroke({{2.5f, 4.5f}, {6.5f, 4.5f}, {6.5f, 2.5f}})};
    place_on_depth_edges(s, toward, away);
    EXPECT_FLOAT_EQ(s[0].points[0].y, 5.0f);  // on the border with row 5 (far)
    EXPECT_FLOAT_EQ(s[0].points[0].x, 2.5f);
    EXPECT_FLOAT_EQ(s[0].points[1].y, 5.0f);
    EXPECT_FLOAT_EQ(s[0].points[2].y, 2.5f);  // inside the occluder: no far neighbour
}

TEST(DepthEdgePlacement, DiagonalEdgeMovesAlongTheDiagonal) {
    DepthImage toward = image(10, 10, 100.0f), away = image(10, 10, 20.0f);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x)
            if (x + y <= 8) at(toward, x, y) = 10.0f;  // occluder below the anti-diagonal
    std::vector<Stroke> s = {stroke({{4.5f, 4.5f}})};  // x + y = 8: far neighbours (5,4), (4,5), (5,5)
    place_on_depth_edges(s, toward, away);
    EXPECT_NEAR(s[0].points[0].x, 5.0f, 1e-6);  // sum of offsets (2, 2): 0.5 px along each axis
    EXPECT_NEAR(s[0].points[0].y, 5.0f, 1e-6);
}

TEST(DepthEdgePlacement, NoAwayFragmentBehindLeavesPointsAlone) {
    DepthImage toward = image(10, 10, 100.0f), away = image(10, 10, inf);  // a cut edge: no back face
    for (int y = 0; y <= 4; ++y)
        for (int x = 0; x < 10; ++x) at(toward, x, y) = 10.0f;
    std::vector<Stroke> s = {stroke({{2.5f, 4.5f}})};
    place_on_depth_edges(s, toward, away);
    EXPECT_FLOAT_EQ(s[0].points[0].y, 4.5f);
}
