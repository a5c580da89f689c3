// Ray-cast reference silhouettes on hand geometry with exact answers: a square in front of a wall
// has its projected outline as silhouette (every split point within a quarter sample of it, the
// total length the perimeter's), a wall alone has none, and a square flagged as cut draws nothing.
#include <cmath>

#include <gtest/gtest.h>

#include "lines/raycast_silhouettes.hpp"

using namespace penink;

namespace {

Camera looking_north() {  // eye at the origin, 90 degree fov, 100 x 100 px
    Camera c;
    c.eye = {0.0, 0.0, 0.0}, c.azimuth = 0.0, c.altitude = 0.0, c.fov = 90.0;
    c.width = 100, c.height = 100, c.near_plane = 1.0, c.far_plane = 1000.0;
    return c;
}

// Two triangles of the square |x|, |z| <= half at distance y.
void add_square(std::vector<glm::vec3>& pos, std::vector<glm::uvec3>& tri, float y, float half) {
    const unsigned b = unsigned(pos.size());
    pos.insert(pos.end(), {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}});
    tri.push_back({b, b + 1, b + 2}), tri.push_back({b, b + 2, b + 3});
}

double length(const std::vector<std::vector<glm::vec2>>& lines) {
    double l = 0;
    for (const auto& line : lines)
        for (std::size_t i = 1; i < line.size(); ++i) l += glm::length(line[i] - line[i - 1]);
    return l;
}

}  // namespace

TEST(RaycastSilhouettes, SquareBeforeAWallGivesItsOutline) {
    std::vector<glm::vec3> pos;
    std::vector<glm::uvec3> tri;
    add_square(pos, tri, 10.0f, 2.0f);     // projects to |u| <= 0.2 of the half-width: x, y in [40, 60] px
    add_square(pos, tri, 100.0f, 200.0f);  // a wall filling the view
    const Camera cam = looking_north();
    const auto lines = raycast_silhouettes(pos, tri, {}, cam, {});
    ASSERT_FALSE(lines.empty());
    for (const auto& line : lines)
        for (const glm::vec2 p : line) {  // on the outline: x or y at 40 or 60, within 1/8 px (half a sample)
            const double d = std::min({std::abs(p.x - 40.0), std::abs(p.x - 60.0), std::abs(p.y - 40.0), std::abs(p.y - 60.0)});
            EXPECT_LE(d, 0.125 + 1e-4) << p.x << " " << p.y;
            EXPECT_GE(std::min(p.x, p.y), 40.0 - 0.125 - 1e-4);
            EXPECT_LE(std::max(p.x, p.y), 60.0 + 0.125 + 1e-4);
        }
    EXPECT_NEAR(length(lines), 80.0, 1.0);  // perimeter 4 x 20 px (corners cut by a quarter pixel)
}

TEST(RaycastSilhouettes, ContinuousSurfaceHasNone) {
    std::vector<glm::vec3> pos;
    std::vector<glm::uvec3> tri;
    add_square(pos, tri, 100.0f, 200.0f);
    EXPECT_TRUE(raycast_silhouettes(pos, tri, {}, looking_north(), {}).empty());
}

TEST(RaycastSilhouettes, CutTrianglesAreNotSilhouettes) {
    std::vector<glm::vec3> pos;
    std::vector<glm::uvec3> tri;
    add_square(pos, tri, 10.0f, 2.0f);
    add_square(pos, tri, 100.0f, 200.0f);
    EXPECT_TRUE(raycast_silhouettes(pos, tri, {1, 1, 0, 0}, looking_north(), {}).empty());
}
