// The direction measures of a plan view's layers (scene/plan_directions.hpp): strokes in pixels
// taken to the Terrain's local metres through the drawing's georeference.
#include <gtest/gtest.h>

#include "input/dem_reader.hpp"
#include "scene/plan_directions.hpp"

namespace penink {
namespace {

const std::string dem = PENINK_SOURCE_DIR "/examples/volcano.asc";

// A drawing whose pixel (col, row) is local (col, -row) metres from the DEM's middle node
// (1 m a pixel, north up), with one stroke of 2 px segments in the creases layer from pixel
// `a` to pixel `b`.
Drawing drawing_with(const Terrain& t, glm::vec2 a, glm::vec2 b) {
    const glm::vec3 mid = t.pos[t.index(t.cols / 2, t.rows / 2)];
    Drawing d;
    d.width = d.height = 400;
    Georeference g;
    g.geotransform = {t.origin.x + mid.x - 200.0, 1.0, 0.0, t.origin.y + mid.y + 200.0, 0.0, -1.0};
    d.georeference = g;
    Stroke s;
    s.kind = "crease";
    for (int k = 0; k <= 50; ++k) s.points.push_back(a + (b - a) * (float(k) / 50.0f)), s.depth.push_back(1.0f);
    d.layer(LayerKind::creases).strokes.push_back(s);
    return d;
}

TEST(PlanDirections, StrokesAreMeasuredInTheDemsFrame) {
    const Terrain t = read_dem(dem);
    // along a row of the DEM (its cells are square and north up): all of it in grid runs
    const auto along = plan_view_directions(drawing_with(t, {150, 200}, {250, 200}), dem);
    ASSERT_EQ(along.size(), 1u);
    EXPECT_EQ(along[0].kind, LayerKind::creases);
    EXPECT_NEAR(along[0].directions.grid_share(), 1.0, 1e-12);
    EXPECT_NEAR(along[0].directions.length, 100.0, 1e-3);  // 1 m a pixel
    // at 30 degrees to the rows (-30 in the image's y-down pixels): no grid run
    const auto slanted = plan_view_directions(drawing_with(t, {150, 200}, {150 + 86.6f, 150}), dem);
    ASSERT_EQ(slanted.size(), 1u);
    EXPECT_EQ(slanted[0].directions.grid_length, 0.0);
}

TEST(PlanDirections, OnlyPlanViewsAreMeasured) {
    const Terrain t = read_dem(dem);
    Drawing d = drawing_with(t, {150, 200}, {250, 200});
    d.georeference.reset();
    EXPECT_TRUE(plan_view_directions(d, dem).empty());
}

}  // namespace
}  // namespace penink
