// The terrain camera aimed at a target ([camera] target, distance; scene/scene.hpp): from a
// position it looks straight at the target's ground point, without one it stands `distance`
// back from it along azimuth and altitude; either way the target lands in the image's centre.
// Keys of the other kind of scene are errors naming them.
#include <cmath>
#include <fstream>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "input/dem_reader.hpp"
#include "scene/scene.hpp"
#include "scene/terrain_view.hpp"
#include "support/temp_dir.hpp"
#include "surface/grid_ground.hpp"

namespace penink {
namespace {

const Terrain& volcano() {  // NZTM2000, 10 m cells, upper-left corner 1756970 E 5917870 N
    static const Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    return t;
}

Scene scene_from(const test::TempDir& dir, const std::string& camera_keys) {
    const std::string path = dir.file("s.toml");
    std::ofstream(path) << "[terrain]\ndem = \"" PENINK_SOURCE_DIR "/examples/volcano.asc\"\nvertical_exaggeration = 2\n"
                        << "[camera]\nwidth = 400\nheight = 300\n" << camera_keys;
    Scene s = load_scene(path);
    validate_scene(s);
    return s;
}

// The image point of a world point (pixels, y down).
glm::dvec2 image_point(const Camera& cam, const glm::dvec3& p) {
    const glm::dvec4 c = view_projection(cam) * glm::dvec4(p, 1.0);
    return {(c.x / c.w * 0.5 + 0.5) * cam.width, (0.5 - c.y / c.w * 0.5) * cam.height};
}

// The volcano drawn at exaggeration 2.
Terrain volcano_at_2() {
    Terrain t = volcano();
    t.vertical_exaggeration = 2.0;
    return t;
}

// The target's ground point as drawn: local metres of "1757300 5917500".
glm::dvec3 target_point() {
    const Terrain t = volcano_at_2();
    const glm::dvec2 xy{1757300.0 - t.origin.x, 5917500.0 - t.origin.y};
    double ground = 0.0;
    EXPECT_TRUE(grid_ground_height(grid_nodes(t), xy.x, xy.y, ground));
    return {xy, ground};
}

TEST(CameraTarget, FromAPositionTheCameraAimsAtTheTarget) {
    test::TempDir dir;
    const Scene s = scene_from(dir, "position = \"1757000 5917100\"\nelevation = 400\ntarget = \"1757300 5917500\"\n");
    const Camera cam = scene_camera(s, volcano_at_2());
    // Bearing of (300 E, 400 N): atan2(300, 400) = 36.870 degrees clockwise from north.
    EXPECT_NEAR(cam.azimuth, std::atan2(300.0, 400.0) * 180.0 / M_PI, 1e-9);
    EXPECT_LT(cam.altitude, 0.0);  // 800 m (exaggerated) above ground 200-400 m: looking down
    const glm::dvec2 c = image_point(cam, target_point());
    EXPECT_NEAR(c.x, 200.0, 1e-6);  // the target in the centre, to rounding
    EXPECT_NEAR(c.y, 150.0, 1e-6);
}

TEST(CameraTarget, WithoutAPositionTheCameraStandsItsDistanceBack) {
    test::TempDir dir;
    const Scene s = scene_from(dir, "target = \"1757300 5917500\"\ndistance = 900\nazimuth = 200\naltitude = -20\n");
    const Camera cam = scene_camera(s, volcano_at_2());
    EXPECT_DOUBLE_EQ(cam.azimuth, 200.0);
    EXPECT_DOUBLE_EQ(cam.altitude, -20.0);
    EXPECT_NEAR(glm::length(cam.eye - target_point()), 900.0, 1e-9);
    const glm::dvec2 c = image_point(cam, target_point());
    EXPECT_NEAR(c.x, 200.0, 1e-6);
    EXPECT_NEAR(c.y, 150.0, 1e-6);
}

TEST(CameraTarget, AnOrthographicViewIsCentredOnItsTarget) {
    test::TempDir dir;
    const Scene s = scene_from(dir, "projection = \"orthographic\"\naltitude = -90\nazimuth = 0\ntarget = \"1757300 5917500\"\n");
    const Camera cam = scene_camera(s, volcano_at_2());
    const glm::dvec2 c = image_point(cam, target_point());
    EXPECT_NEAR(c.x, 200.0, 1e-6);
    EXPECT_NEAR(c.y, 150.0, 1e-6);
}

void expect_error(const test::TempDir& dir, const std::string& keys, const std::string& what, bool mesh = false) {
    const std::string path = dir.file("e.toml");
    std::ofstream(path) << (mesh ? "[mesh]\nfile = \"m.obj\"\n" : "[terrain]\ndem = \"d.asc\"\n") << "[camera]\n" << keys;
    try {
        Scene s = load_scene(path);
        validate_scene(s);
        ADD_FAILURE() << "accepted: " << keys;
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: scene: " + path + ": " + what);
    }
}

TEST(CameraTarget, KeysOfTheOtherKindOfSceneAreErrors) {
    test::TempDir dir;
    expect_error(dir, "eye = [0, 0, 10]\n",
                 "[camera] eye applies to mesh scenes only (a terrain's camera takes position, elevation, azimuth, "
                 "altitude, target = \"PLACE\" and distance)");
    expect_error(dir, "target = [0, 0, 10]\n",
                 "[camera] target: expected a place (\"LON,LAT\", \"EASTING NORTHING ZONE\" or \"X Y\")");
    expect_error(dir, "position = \"0 0\"\nelevation = 5\n",
                 "[camera] position applies to terrain scenes only (a mesh's camera takes eye, target = [x, y, z] and up)",
                 true);
    expect_error(dir, "target = \"0 0\"\n",
                 "[camera] target as a place applies to terrain scenes only (a mesh's camera takes eye, target = [x, y, "
                 "z] and up)",
                 true);
}

TEST(CameraTarget, ConflictingPlacementsAreErrors) {
    test::TempDir dir;
    expect_error(dir, "position = \"0 0\"\nelevation = 5\ntarget = \"1 1\"\nazimuth = 10\n",
                 "camera azimuth and altitude follow from position and target: give one or the other");
    expect_error(dir, "distance = 100\n", "camera distance goes with a target (the place looked at)");
    expect_error(dir, "position = \"0 0\"\nelevation = 5\ntarget = \"1 1\"\ndistance = 100\n",
                 "camera distance and position both place the camera: give one");
    expect_error(dir, "target = \"1 1\"\ndistance = -3\n", "[camera] distance must be between 0.001 and 1e+08 metres (got -3)");
}

}  // namespace
}  // namespace penink
