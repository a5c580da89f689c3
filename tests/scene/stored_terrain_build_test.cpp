// A DEM's terrain cache built by open_stored_terrain (scene/terrain_view.hpp): streamed to the
// cache folder and opened from it, its nodes and pyramid those of the whole Terrain read and
// built in memory (store_terrain), value for value; where nothing can be written (the cache
// folder is a regular file) the terrain built in memory, the same values, and no file.
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/log.hpp"
#include "input/dem_reader.hpp"
#include "scene/terrain_view.hpp"
#include "surface/terrain_cache.hpp"
#include "support/temp_dir.hpp"

using namespace penink;

namespace {

// The volcano copied into `dir` (no cache beside it), its path.
std::string copy_volcano(const test::TempDir& dir) {
    for (const char* ext : {".asc", ".prj"})
        std::filesystem::copy_file(std::string(PENINK_SOURCE_DIR "/examples/volcano") + ext, dir.file(std::string("volcano") + ext));
    return dir.file("volcano.asc");
}

void expect_same_terrain(const StoredTerrain& a, const StoredTerrain& b) {
    read_whole(a), read_whole(b);
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    ASSERT_EQ(a.lod.error.size(), b.lod.error.size());
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        ASSERT_EQ(a.nodes.valid[i], b.nodes.valid[i]) << i;
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ(std::bit_cast<std::uint32_t>(a.nodes.pos[i][k]), std::bit_cast<std::uint32_t>(b.nodes.pos[i][k])) << i;
    }
    for (std::size_t i = 0; i < a.lod.error.size(); ++i)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(a.lod.error[i]), std::bit_cast<std::uint32_t>(b.lod.error[i])) << i;
    EXPECT_EQ(a.lod.lipschitz, b.lod.lipschitz);
    EXPECT_EQ(a.lod.z_min, b.lod.z_min);
    EXPECT_EQ(a.lod.z_max, b.lod.z_max);
    EXPECT_EQ(a.plan_lo, b.plan_lo);
    EXPECT_EQ(a.plan_hi, b.plan_hi);
}

}  // namespace

TEST(StoredTerrainBuild, StreamedToTheCacheFolderAndOpenedFromIt) {
    test::TempDir dir, cache("stored_terrain_build_cache");
    const std::string volcano = copy_volcano(dir);
    const StoredTerrain built = open_stored_terrain(volcano, Log{}, cache.path.string());
    EXPECT_EQ(built.in_memory, nullptr);  // opened from the file written
    int files = 0;
    for (const auto& f : std::filesystem::directory_iterator(cache.path)) files += f.path().extension() == ".lod";
    EXPECT_EQ(files, 1);
    expect_same_terrain(built, store_terrain(read_dem(volcano)));
    // keyed as a warm open is: the drainage fingerprint takes the key instead of hashing the DEM again
    EXPECT_TRUE(built.key == terrain_cache_key(volcano));
    EXPECT_NE(built.key.content_hash, 0u);
    EXPECT_TRUE(open_stored_terrain(volcano, Log{}, cache.path.string()).key == built.key);
}

TEST(StoredTerrainBuild, WhereNothingCanBeWrittenTheTerrainIsBuiltInMemory) {
    test::TempDir dir;
    const std::string volcano = copy_volcano(dir);
    const std::string blocker = dir.file("not-a-folder");
    std::ofstream(blocker) << "x";
    const StoredTerrain built = open_stored_terrain(volcano, Log{}, blocker);
    EXPECT_NE(built.in_memory, nullptr);
    EXPECT_EQ(std::filesystem::file_size(blocker), 1u);
    expect_same_terrain(built, store_terrain(read_dem(volcano)));
}
