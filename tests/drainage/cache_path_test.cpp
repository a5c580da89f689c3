// Where the drainage cache of a DEM lives: in the cache folder given (--cache-dir, [cache] dir);
// else beside a DEM in a writable folder that is not under an install prefix; else in the user's
// cache folder ($XDG_CACHE_HOME/penink, else ~/.cache/penink) under a name made from the file name
// and a hash of its absolute path. A cache beside a DEM in a read-only folder is still read.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "drainage/drainage_build.hpp"
#include "support/read_only_dir.hpp"
#include "support/temp_dir.hpp"

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

TEST(DrainageCachePath, InTheCacheFolderGiven) {
    test::TempDir dir;
    const std::string folder = dir.file("caches/deep");  // made when missing
    const std::string dem = dir.file("dem.tif");
    const std::string p = drainage_cache_path(dem, folder);
    EXPECT_EQ(p, cache_file_in(folder, dem));
    EXPECT_EQ(p.rfind(folder + "/dem.tif-", 0), 0u) << p;
    EXPECT_EQ(p.size(), folder.size() + std::string("/dem.tif-").size() + 16 + 3);
    EXPECT_TRUE(std::filesystem::is_directory(folder));
    EXPECT_NE(drainage_cache_path(dir.file("other/dem.tif"), folder), p);  // same name, another DEM
}

TEST(DrainageCachePath, InstallPrefix) {
    EXPECT_TRUE(under_install_prefix("/usr/share/penink/examples", "/usr"));
    EXPECT_TRUE(under_install_prefix("/usr/share/penink/examples", "/usr/"));
    EXPECT_TRUE(under_install_prefix("/usr", "/usr"));
    EXPECT_TRUE(under_install_prefix("/usr/local/share/../share/penink", "/usr/local"));
    EXPECT_FALSE(under_install_prefix("/usrx/share", "/usr"));
    EXPECT_FALSE(under_install_prefix("/home/u/dem", "/usr"));
    EXPECT_FALSE(under_install_prefix("/home/u/dem", "/"));  // a prefix of / would take every folder
    EXPECT_FALSE(under_install_prefix("/usr/share", ""));
}

// Not under a prefix, not writable: the user's cache folder ($XDG_CACHE_HOME, else ~/.cache).
TEST(DrainageCachePath, UserCacheFolderFromTheEnvironment) {
    test::TempDir dir;
    const std::string dem = "/usr/share/penink-test-nowhere/dem.tif";  // a folder that does not exist: not writable
    const char* old_xdg = std::getenv("XDG_CACHE_HOME");
    const char* old_home = std::getenv("HOME");
    const std::string keep_xdg = old_xdg ? old_xdg : "", keep_home = old_home ? old_home : "";
    ::setenv("XDG_CACHE_HOME", dir.file("xdg").c_str(), 1);
    EXPECT_EQ(drainage_cache_path(dem), cache_file_in(dir.file("xdg/penink"), dem));
    EXPECT_TRUE(std::filesystem::is_directory(dir.file("xdg/penink")));
    ::unsetenv("XDG_CACHE_HOME");
    ::setenv("HOME", dir.file("home").c_str(), 1);
    EXPECT_EQ(drainage_cache_path(dem), cache_file_in(dir.file("home/.cache/penink"), dem));
    if (old_xdg) ::setenv("XDG_CACHE_HOME", keep_xdg.c_str(), 1);
    if (old_home) ::setenv("HOME", keep_home.c_str(), 1);
    else ::unsetenv("HOME");
}

// -v names each cache with its size.
TEST(DrainageCachePath, ReportNamesPathAndSize) {
    test::TempDir dir;
    const std::string f = dir.file("x.dv");
    std::ofstream(f) << std::string(3000, 'x');
    EXPECT_EQ(cache_file_report(f), f + " (3 KiB)");
    EXPECT_EQ(cache_file_report(dir.file("none.dv")), dir.file("none.dv"));
}

namespace {

Terrain small_dem() {
    Terrain t;
    t.cols = 6, t.rows = 5, t.origin = {500000.0, 4000000.0};
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c) {
            t.pos.emplace_back(c * 10.0f, -r * 10.0f, float((c - 3) * (c - 3) + r));
            t.valid.push_back(1);
        }
    return t;
}

}  // namespace

// A cache beside a DEM whose folder is read-only is read (not rebuilt), though the cache path is
// the user's cache folder; with a cache folder given, it is read too.
TEST(DrainageCachePath, ReadOnlyFolderCacheIsStillRead) {
    test::TempDir dir;
    test::ReadOnlyDir ro(dir.path / "ro");
    const std::string dem = (ro.path() / "dem.asc").string();
    std::ofstream(dem) << "ncols 6\nnrows 5\nxllcorner 0\nyllcorner 0\ncellsize 10\n"
                          "9 4 1 0 1 4\n10 5 2 1 2 5\n11 6 3 2 3 6\n12 7 4 3 4 7\n13 8 5 4 5 8\n";
    const Terrain t = small_dem();
    const DrainageOptions options;
    std::vector<std::string> said;
    const DrainageLog log = [&](const std::string& m) { said.push_back(m); };
    load_or_build_drainage(dem, t, options, log);  // written beside (the folder is writable yet)
    ASSERT_TRUE(std::filesystem::exists(dem + ".dv"));
    if (!ro.seal()) GTEST_SKIP() << ro.reason;
    ::setenv("XDG_CACHE_HOME", dir.file("xdg").c_str(), 1);
    ASSERT_NE(drainage_cache_path(dem), dem + ".dv");
    said.clear();
    load_or_build_drainage(dem, t, options, log);
    ASSERT_FALSE(said.empty());
    EXPECT_EQ(said.front().rfind("drainage: using cached " + dem + ".dv (", 0), 0u) << said.front();
    DrainageOptions in_folder;
    in_folder.cache_dir = dir.file("caches");
    said.clear();
    load_or_build_drainage(dem, t, in_folder, log);
    EXPECT_EQ(said.front().rfind("drainage: using cached " + dem + ".dv (", 0), 0u) << said.front();
    ::unsetenv("XDG_CACHE_HOME");
}
