// Plan views' pixel -> map transform: corners of the image land where the camera puts them, north
// up or rotated, and oblique or perspective views have none; the metadata that says so, and the
// exact decimals it is written with.
#include <gtest/gtest.h>

#include <sstream>

#include "core/georeference.hpp"

using namespace penink;

TEST(Georeference, NorthUpPlanViewMapsPixelCornersToMapMetres) {
    const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1000, 500, 100}};
    const Camera c = frame_points_orthographic(pts, {.azimuth = 0.0, .altitude = -90.0, .width = 800, .height = 400, .view_width = 2000.0});
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
    const Camera c = frame_points_orthographic(pts, {.azimuth = 90.0, .altitude = -90.0, .width = 500, .height = 500, .view_width = 1000.0});  // east up
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
    EXPECT_FALSE(plan_view_georeference(frame_points_orthographic(pts, {.azimuth = 0.0, .altitude = -60.0, .width = 500, .height = 500}), {0, 0}, ""));
    EXPECT_FALSE(plan_view_georeference(frame_points(pts, {.azimuth = 0.0, .altitude = -90.0, .fov = 40.0, .width = 500, .height = 500}), {0, 0}, ""));
}

TEST(Georeference, MetadataSaysWhetherAndHowTheViewIsGeoreferenced) {
    const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1000, 500, 100}};
    const Camera oblique = frame_points_orthographic(pts, {.azimuth = 0.0, .altitude = -60.0, .width = 500, .height = 500});
    const Camera perspective = frame_points(pts, {.azimuth = 0.0, .altitude = -90.0, .fov = 40.0, .width = 500, .height = 500});
    EXPECT_EQ(georeference_metadata(oblique, std::nullopt),
              (std::map<std::string, std::string>{{"georeferenced", "no (oblique view)"}}));
    EXPECT_EQ(georeference_metadata(perspective, std::nullopt),
              (std::map<std::string, std::string>{{"georeferenced", "no (perspective view)"}}));
    const Camera plan = frame_points_orthographic(pts, {.azimuth = 30.0, .altitude = -90.0, .width = 500, .height = 400, .view_width = 1000.0});
    const auto g = plan_view_georeference(plan, {500000.0, 4000000.0}, "WKT");
    const auto m = georeference_metadata(plan, g);
    EXPECT_EQ(m.at("georeferenced"), "yes (plan view)");
    EXPECT_EQ(m.at("crs"), "WKT");
    std::istringstream in(m.at("geotransform"));
    for (int i = 0; i < 6; ++i) {
        double v = 0;
        in >> v;
        EXPECT_EQ(v, g->geotransform[i]) << i;  // rotated: no term is tidied; the decimals read back exactly
    }
    const auto local = georeference_metadata(plan, plan_view_georeference(plan, {0, 0}, ""));
    EXPECT_EQ(local.at("georeferenced"), "yes (plan view, local coordinates without a CRS)");
    EXPECT_EQ(local.count("crs"), 0u);
}

TEST(Georeference, ExactDecimalsReadBackAndNorthUpRotationIsTidied) {
    for (double v : {0.1, -1756970.123456789, 6.123233995736766e-17, 2.5, 1e-300, -0.0}) {
        const std::string s = exact_decimal(v);
        EXPECT_EQ(s.find_first_of("eE"), std::string::npos) << s;
        EXPECT_EQ(std::stod(s), v == 0.0 ? 0.0 : v) << s;
    }
    EXPECT_EQ(exact_decimal(-0.0), "0");
    const auto t = tidy_geotransform({500000.0, 10.0, 6e-16, 4000000.0, -6e-16, -10.0});
    EXPECT_EQ(t, (std::array<double, 6>{500000.0, 10.0, 0.0, 4000000.0, 0.0, -10.0}));
    const auto kept = tidy_geotransform({0.0, 10.0, 1e-6, 0.0, 1e-6, -10.0});  // a real (tiny) rotation stays
    EXPECT_EQ(kept[2], 1e-6);
}
