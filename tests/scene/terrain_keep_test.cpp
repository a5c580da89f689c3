// A DEM's first drawing builds its terrain cache and drainage database side by side
// (TerrainKeep::build_side_by_side, scene/terrain_keep.hpp): the same files, byte for byte, as
// one after the other, kept so that the drawing builds and reads nothing again; only for a first
// drawing (nothing on disk, nothing kept) of a scene with creases or ridges of a DEM over the
// size given; a DEM that cannot be read fails with the terrain cache's error, as one after the
// other, and leaves no cache. The DEM is a geographic GeoTIFF over 1 M cells, so the drainage is
// built at factor 1 and its creases' source refers to the DEM's heights in the UTM zone a read
// of the DEM alone finds (what the side-by-side build knows of the DEM before it is read: its size).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/log.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/drainage_db.hpp"
#include "scene/scene.hpp"
#include "scene/terrain_keep.hpp"
#include "support/temp_dir.hpp"
#include "support/test_grids.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

std::string bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// 1100 x 1000 cells of 1/3" near 36.5 N, 84.2 W (Float32, EPSG:4326): ridges and valleys
// crossing a tilted plane, so there are stems, divides and depressions.
std::string write_hills(const test::TempDir& dir) {
    const int cols = 1100, rows = 1000;
    std::vector<float> z(std::size_t(cols) * rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            z[std::size_t(r) * cols + c] = float(400.0 + 0.05 * c - 0.03 * r + 40.0 * std::sin(c / 37.0) * std::cos(r / 53.0) +
                                                 15.0 * std::sin((c + 2 * r) / 19.0));
    const double cell = 1.0 / 10800.0;
    return test::write_tif(dir.file("hills.tif"), cols, rows, z, {-84.25, cell, 0.0, 36.55, 0.0, -cell}, 4326);
}

Scene scene_of(const std::string& dem) {
    Scene s;
    s.source.dem = dem;
    s.view.camera.width = 320, s.view.camera.height = 240;
    return s;
}

void remove_caches(const std::string& dem) {
    for (const char* ext : {".lod", ".dv", ".dv.tiles"}) fs::remove_all(dem + ext);
}

}  // namespace

TEST(TerrainKeep, AFirstDrawingBuildsBothCachesSideBySideAsOneAfterTheOther) {
    const test::TempDir dir("terrain_keep");
    const std::string dem = write_hills(dir);
    Scene scene = scene_of(dem);
    ASSERT_TRUE(scene.lines.creases.enabled || scene.lines.ridges.enabled);
    std::string lod, dv;
    {  // one after the other
        TerrainKeep k;
        const SceneTerrain t = k.terrain(scene, Log{});
        ASSERT_NE(k.drainage(scene, t, Log{}), nullptr);
        lod = bytes_of(dem + ".lod"), dv = bytes_of(dem + ".dv");
    }
    ASSERT_GT(lod.size(), 1000u);
    ASSERT_GT(dv.size(), 1000u);
    remove_caches(dem);

    TerrainKeep k;
    ASSERT_TRUE(k.build_side_by_side(scene, Log{}, 0.0));
    EXPECT_TRUE(bytes_of(dem + ".lod") == lod);
    EXPECT_TRUE(bytes_of(dem + ".dv") == dv);
    const auto written = fs::last_write_time(dem + ".dv");
    // kept: not built again, here or by the drawing that follows
    EXPECT_FALSE(k.build_side_by_side(scene, Log{}, 0.0));
    const SceneTerrain t = k.terrain(scene, Log{});
    const std::shared_ptr<const DrainageLineSource> drainage = k.drainage(scene, t, Log{});
    ASSERT_NE(drainage, nullptr);
    EXPECT_EQ(drainage, k.drainage(scene, t, Log{}));
    EXPECT_NE(drainage->creases, nullptr);
    const DrainageDb db = read_drainage_db(dem + ".dv");  // factor 1: its creases' source refers to the DEM's heights
    ASSERT_TRUE(db.has_crease_source());
    EXPECT_EQ(crease_source_dem(crease_source_bytes(db)), absolute_dem_path(dem));
    EXPECT_EQ(fs::last_write_time(dem + ".dv"), written);
    // on disk: another process draws from the caches
    TerrainKeep other;
    EXPECT_FALSE(other.build_side_by_side(scene, Log{}, 0.0));
}

TEST(TerrainKeep, SideBySideOnlyForALargeDemsFirstDrawingWithCreasesOrRidges) {
    const test::TempDir dir("terrain_keep_not");
    const std::string dem = write_hills(dir);
    Scene scene = scene_of(dem);
    EXPECT_FALSE(TerrainKeep().build_side_by_side(scene, Log{}, 2e6));  // 1.1 M cells: one after the other
    scene.lines.creases.enabled = scene.lines.ridges.enabled = false;
    EXPECT_FALSE(TerrainKeep().build_side_by_side(scene, Log{}, 0.0));  // no drainage to build
    const std::string junk = test::write_text(dir.file("junk.tif"), "not a raster");
    EXPECT_FALSE(TerrainKeep().build_side_by_side(scene_of(junk), Log{}, 0.0));  // its error is the terrain's
    for (const std::string& d : {dem, junk}) {
        EXPECT_FALSE(fs::exists(d + ".lod")) << d;
        EXPECT_FALSE(fs::exists(d + ".dv")) << d;
    }
}

TEST(TerrainKeep, ADemThatCannotBeReadFailsWithTheTerrainCachesErrorAndNoCache) {
    const test::TempDir dir("terrain_keep_nodata");
    std::vector<std::vector<double>> rows(40, std::vector<double>(50, -9999.0));
    const std::string dem = test::write_asc(dir.file("empty.asc"), 50, rows, 0.0, 0.0, 10.0, "NODATA_value -9999\n");
    Scene scene = scene_of(dem);
    std::string one_after_the_other;
    try {
        TerrainKeep().terrain(scene, Log{});
    } catch (const Error& e) {
        one_after_the_other = e.what();
    }
    ASSERT_NE(one_after_the_other, "");
    try {
        TerrainKeep().build_side_by_side(scene, Log{}, 0.0);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), one_after_the_other);
    }
    EXPECT_FALSE(fs::exists(dem + ".lod"));
    EXPECT_FALSE(fs::exists(dem + ".dv"));
}

}  // namespace penink
