// Where the drainage cache of a DEM lives: beside a DEM in a writable folder, else in the user's
// cache folder under a name made from the file name and a hash of its absolute path.
#include <filesystem>

#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"

using namespace penink;

TEST(DrainageCachePath, BesideAWritableDem) {
    EXPECT_EQ(drainage_cache_path("/data/dem.tif", true, "/home/u/.cache"), "/data/dem.tif.dv");
    EXPECT_EQ(drainage_cache_path("dem.tif", true, ""), "dem.tif.dv");
}

TEST(DrainageCachePath, UserCacheForAReadOnlyFolder) {
    const std::string a = drainage_cache_path("/ro/dem.tif", false, "/home/u/.cache");
    const std::string b = drainage_cache_path("/ro/../ro/dem.tif", false, "/home/u/.cache");
    const std::string c = drainage_cache_path("/other/dem.tif", false, "/home/u/.cache");
    EXPECT_EQ(a.rfind("/home/u/.cache/penink/dem.tif-", 0), 0u) << a;
    EXPECT_EQ(a.size(), std::string("/home/u/.cache/penink/dem.tif-").size() + 16 + 3);
    EXPECT_EQ(a.substr(a.size() - 3), ".dv");
    EXPECT_EQ(a, b);  // the same file, however it is spelt
    EXPECT_NE(a, c);  // two DEMs of the same name in different folders
    // No user cache folder known: beside the DEM (the write then fails and is logged).
    EXPECT_EQ(drainage_cache_path("/ro/dem.tif", false, ""), "/ro/dem.tif.dv");
}

TEST(DrainageCachePath, WritableFolderDetected) {
    const auto dir = std::filesystem::temp_directory_path() / "penink_cache_path_test";
    std::filesystem::create_directories(dir);
    const std::string dem = (dir / "dem.tif").string();
    EXPECT_EQ(drainage_cache_path(dem), dem + ".dv");
    std::filesystem::remove_all(dir);
}
