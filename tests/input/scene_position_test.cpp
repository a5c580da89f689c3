#include "input/scene_position.hpp"

#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include "core/error.hpp"
#include "input/dem_reader.hpp"
#include "support/test_grids.hpp"

namespace penink {
namespace {

const Terrain& jacksboro() {
    static const Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    return t;
}

std::string error_of(const std::string& text, const Terrain& t) {
    try {
        parse_scene_position(text, t, "scenes/a.toml");
    } catch (const Error& e) {
        EXPECT_EQ(e.stage(), "scene");
        EXPECT_EQ(e.file(), "scenes/a.toml");
        EXPECT_EQ(e.code(), ExitCode::bad_input);
        return e.what();
    }
    return "no error";
}

std::string parse_error(const std::string& text) {
    return "penink: scene: scenes/a.toml: cannot parse position \"" + text +
           "\" (expected \"EASTING NORTHING ZONE[N|S]\", \"LON,LAT\" or \"X Y\")";
}

TEST(ScenePosition, UtmInTheTerrainZoneIsUsedDirectly) {
    const Terrain& t = jacksboro();
    const glm::dvec2 p = parse_scene_position("735012.5 4067000 16N", t, "a.toml");
    EXPECT_EQ(p, glm::dvec2(735012.5, 4067000) - t.origin);
    EXPECT_EQ(parse_scene_position("  735012.5   4067000 16 n ", t, "a.toml"), p);
}

TEST(ScenePosition, UtmInAnotherZoneIsTransformed) {
    const Terrain& t = jacksboro();
    // A point in zone 17N: GeographicLib's own zone transfer is the reference.
    double x = 0, y = 0;
    int zone = 0;
    GeographicLib::UTMUPS::Transfer(17, true, 230000, 4070000, 16, true, x, y, zone);
    const glm::dvec2 p = parse_scene_position("230000 4070000 17N", t, "a.toml");
    EXPECT_NEAR(p.x, x - t.origin.x, 0.01);
    EXPECT_NEAR(p.y, y - t.origin.y, 0.01);
}

TEST(ScenePosition, LonLatUsesTheTerrainZone) {
    const Terrain& t = jacksboro();
    int zone = 0;
    bool north = false;
    double x = 0, y = 0;
    GeographicLib::UTMUPS::Forward(36.6, -84.25, zone, north, x, y, 16);
    const glm::dvec2 p = parse_scene_position("-84.25, 36.6", t, "a.toml");
    EXPECT_NEAR(p.x, x - t.origin.x, 1e-6);
    EXPECT_NEAR(p.y, y - t.origin.y, 1e-6);
    EXPECT_EQ(parse_scene_position("-84.25,36.6", t, "a.toml"), p);
}

TEST(ScenePosition, XyIsInTheTerrainCrs) {
    const Terrain& t = jacksboro();
    EXPECT_EQ(parse_scene_position("740000 4060000.25", t, "a.toml"), glm::dvec2(740000, 4060000.25) - t.origin);
}

TEST(ScenePosition, LonLatOnANonUtmProjectedTerrain) {
    // Volcano is in NZTM2000 (GRS80 transverse Mercator, CM 173 E, k 0.9996, FE 1.6e6, FN 1e7).
    const Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    const GeographicLib::TransverseMercator nztm(6378137.0, 1 / 298.257222101, 0.9996);
    double x = 0, y = 0;
    nztm.Forward(173.0, -36.8767, 174.7645, x, y);
    const glm::dvec2 p = parse_scene_position("174.7645,-36.8767", t, "a.toml");
    EXPECT_NEAR(p.x, x + 1600000 - t.origin.x, 1.0);
    EXPECT_NEAR(p.y, y + 10000000 - t.origin.y, 1.0);
}

TEST(ScenePosition, GarbageIsAParseError) {
    const Terrain& t = jacksboro();
    for (const char* text : {"hello", "", "1 2 3", "588497 4589846 61N", "588497 4589846 18X", "1,2,3", "1e999 2"})
        EXPECT_EQ(error_of(text, t), parse_error(text));
}

TEST(ScenePosition, TerrainWithoutCrsTakesOnlyXy) {
    test::TempDir dir;
    const Terrain t = read_dem(test::write_asc(dir.file("g.asc"), 2, {{1, 2}, {3, 4}}, 100, 200, 10));
    EXPECT_EQ(parse_scene_position("110 205", t, "a.toml"), glm::dvec2(110, 205) - t.origin);
    const std::string cannot = " into the DEM's coordinate system";
    EXPECT_EQ(error_of("588497 4589846 18N", t),
              "penink: scene: scenes/a.toml: cannot transform position \"588497 4589846 18N\"" + cannot);
    EXPECT_EQ(error_of("-84.2,36.6", t), "penink: scene: scenes/a.toml: cannot transform position \"-84.2,36.6\"" + cannot);
}

TEST(ScenePosition, LatitudeOutOfRangeCannotBeTransformed) {
    EXPECT_EQ(error_of("36.6,-184.2", jacksboro()),
              "penink: scene: scenes/a.toml: cannot transform position \"36.6,-184.2\" into the DEM's coordinate system");
}

}  // namespace
}  // namespace penink
