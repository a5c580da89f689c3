// Plan views' pixel -> map transform: corners of the image land where the camera puts them, north
// up or rotated, and oblique or perspective views have none.
#include <gtest/gtest.h>

#include "core/georeference.hpp"

using namespace penink;

TEST(Georeference, NorthUpPlanViewMapsPixelCornersToMapMetres) {
    const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1000, 500, 100}};
    const Camera c = frame_points_orthographic(pts, 0.0, -90.0, 800, 400, 2000.0);
    const auto g = plan_view_georeference(c, {500000.0, 4000000.0}, "WKT");
    ASSERT_TRUE(g);
    EXPECT_EQ(g->crs_wkt, "WKT");
    EXPECT_NEAR(g->geotransform[1], 2.5, 1e-12);   // 2000 m over 800 px
    EXPECT_NEAR(g->geotransform[5], -2.5, 1e-12);  // rows go south
    EXPECT_NEAR(g->geotransform[2], 0.0, 1e-12);
    EXPECT_NEAR(g->geotransform[4], 0.0, 1e-12);
    // The image centre is the points' plan centre; pixel corners follow.
    const glm::dvec2 centre = map_point(*g, 400, 200);
    EXPECT_NEAR(centre.x, 500500.0, 1e-6);
    EXPECT_NEAR(centre.y, 4000250.0, 1e-6);
    // A world point's pixel and the transform agree.
    glm::dvec2 px;
    double d = 0;
    ASSERT_TRUE(project_to_pixel(c, {1000, 500, 30}, px, d));
    const glm::dvec2 m = map_point(*g, px.x, px.y);
    EXPECT_NEAR(m.x, 501000.0, 1e-6);
    EXPECT_NEAR(m.y, 4000500.0, 1e-6);
}

TEST(Georeference, RotatedPlanViewIsARotatedAffineTransform) {
    const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1000, 500, 100}};
    const Camera c = frame_points_orthographic(pts, 90.0, -90.0, 500, 500, 1000.0);  // east up
    const auto g = plan_view_georeference(c, {0.0, 0.0}, "");
    ASSERT_TRUE(g);
    for (const glm::dvec3 p : {glm::dvec3(0, 0, 0), glm::dvec3(1000, 500, 0), glm::dvec3(250, 100, 40)}) {
        glm::dvec2 px;
        double d = 0;
        ASSERT_TRUE(project_to_pixel(c, p, px, d));
        const glm::dvec2 m = map_point(*g, px.x, px.y);
        EXPECT_NEAR(m.x, p.x, 1e-6);
        EXPECT_NEAR(m.y, p.y, 1e-6);
    }
    EXPECT_NEAR(g->geotransform[1], 0.0, 1e-12);  // going right is going south
    EXPECT_NEAR(g->geotransform[4], -2.0, 1e-12);
}

TEST(Georeference, ObliqueAndPerspectiveViewsHaveNone) {
    const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1000, 500, 100}};
    EXPECT_FALSE(plan_view_georeference(frame_points_orthographic(pts, 0.0, -60.0, 500, 500), {0, 0}, ""));
    EXPECT_FALSE(plan_view_georeference(frame_points(pts, 0.0, -90.0, 40.0, 500, 500), {0, 0}, ""));
}
