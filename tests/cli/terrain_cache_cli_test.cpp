// The terrain cache from the command line: `penink drainage DEM` leaves it beside the DEM, and a
// render reads it there even when that folder cannot be written (as user nobody when the tests
// run as root), building neither cache again; the crease tiles its frame builds go to the user's
// cache folder, where the next render reads them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "cli_support.hpp"

namespace fs = std::filesystem;
using namespace penink::test;

namespace {

std::size_t files_named(const fs::path& dir, const std::string& extension) {
    std::size_t n = 0;
    for (auto& e : fs::recursive_directory_iterator(dir)) n += e.path().extension() == extension;
    return n;
}

}  // namespace

TEST(TerrainCacheCli, ReadBesideTheDemInAReadOnlyFolder) {
    const auto dir = fresh_dir("terrain_cache_ro");
    fs::create_directories(dir / "ro");
    fs::create_directories(dir / "home");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "ro" / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "ro" / "volcano.prj");
    const RunResult built = run_penink("drainage ro/volcano.asc", dir);
    ASSERT_EQ(built.code, 0) << built.output;
    EXPECT_NE(built.output.find("drainage: terrain cache ro/volcano.asc.lod\n"), std::string::npos) << built.output;
    ASSERT_TRUE(fs::exists(dir / "ro" / "volcano.asc.lod"));
    // and the crease tiles of the default whole view (1000x750)
    const std::size_t tiles = files_named(dir / "ro", ".pnlt");
    EXPECT_GT(tiles, 0u) << built.output;
    for (const fs::path& p : {dir, dir / "home"}) fs::permissions(p, fs::perms::all);
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                    fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
    const RunResult r = run_penink_unprivileged("render ro/volcano.asc -o out.svg --width 200 --height 150 -v", dir);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: terrain: using cached ro/volcano.asc.lod"), std::string::npos) << r.output;
    // neither cache built again; the crease tiles, which cannot go beside the cache, go to the
    // user's cache folder ($HOME/.cache/penink here)
    EXPECT_EQ(r.output.find("building drainage database"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("wrote"), std::string::npos) << r.output;
    EXPECT_EQ(files_named(dir / "home", ".lod"), 0u) << "built again into the user's cache";
    EXPECT_EQ(files_named(dir / "ro", ".pnlt"), tiles);
    if (!std::getenv("XDG_CACHE_HOME")) {
        EXPECT_GT(files_named(dir / ".cache" / "penink", ".pnlt"), 0u) << r.output;
        EXPECT_EQ(files_named(dir / ".cache" / "penink", ".dv"), 0u);
        const RunResult again = run_penink_unprivileged("render ro/volcano.asc -o out2.svg --width 200 --height 150 -v", dir);
        EXPECT_NE(again.output.find("tile files read, 0 written"), std::string::npos) << again.output;
        EXPECT_EQ(read_text(dir / "out.svg"), read_text(dir / "out2.svg"));
    }
    EXPECT_TRUE(fs::exists(dir / "out.svg"));
    fs::permissions(dir / "ro", fs::perms::owner_write, fs::perm_options::add);
    fs::remove_all(dir);
}
