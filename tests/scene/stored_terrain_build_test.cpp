// A DEM's terrain cache built by open_stored_terrain (scene/terrain_view.hpp): streamed to the
// cache folder and opened from it, its nodes and pyramid those of the whole Terrain read and
// built in memory (store_terrain), value for value; where nothing can be written (the cache
// folder is a regular file) the terrain built in memory, the same values, and no file.
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "core/log.hpp"
#include "input/dem_file_identity.hpp"
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

// A warm open takes the key the cache recorded with the DEM's identity instead of hashing the DEM
// (known_terrain_key); once the DEM is written (its bytes changed, its mtime put back) the identity
// differs, the DEM is hashed, the cache found stale and built again; a copy of the DEM with its
// cache beside it is hashed once (another inode), finds the cache sound and records the copy's
// identity in it, so the next open reads the key alone; so does a link made to the DEM (its
// status changed, its bytes not).
TEST(StoredTerrainBuild, AnUnchangedDemIsNotHashedAgain) {
    test::TempDir dir, cache("stored_terrain_identity_cache");
    const std::string volcano = copy_volcano(dir);
    EXPECT_FALSE(known_terrain_key(volcano, cache.path.string()));  // no cache yet
    const StoredTerrain built = open_stored_terrain(volcano, Log{}, cache.path.string());
    const std::optional<TerrainCacheKey> known = known_terrain_key(volcano, cache.path.string());
    ASSERT_TRUE(known);
    EXPECT_TRUE(*known == built.key);
    EXPECT_EQ(known->identity, built.key.identity);
    EXPECT_NE(known->identity, 0u);
    EXPECT_TRUE(open_stored_terrain(volcano, Log{}, cache.path.string()).key == built.key);

    // one height changed in place, same size, mtime put back
    struct stat st {};
    ASSERT_EQ(::stat(volcano.c_str(), &st), 0);
    std::string text;
    {
        std::ifstream in(volcano, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::size_t at = text.rfind("100");
    ASSERT_NE(at, std::string::npos);
    text[at] = '2';  // 100 m -> 200 m
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::ofstream(volcano, std::ios::binary | std::ios::trunc) << text;
    const timespec times[2] = {st.st_atim, st.st_mtim};
    ASSERT_EQ(::utimensat(AT_FDCWD, volcano.c_str(), times, 0), 0);
    EXPECT_FALSE(known_terrain_key(volcano, cache.path.string()));
    const StoredTerrain rebuilt = open_stored_terrain(volcano, Log{}, cache.path.string());
    EXPECT_NE(rebuilt.key.content_hash, built.key.content_hash);
    EXPECT_EQ(rebuilt.key.mtime_ns, built.key.mtime_ns);
    expect_same_terrain(rebuilt, store_terrain(read_dem(volcano)));
    ASSERT_TRUE(known_terrain_key(volcano, cache.path.string()));

    // the DEM (its mtime kept) and its cache copied elsewhere: not known by identity, hashed, the cache sound
    test::TempDir other("stored_terrain_identity_other");
    for (const char* ext : {".asc", ".prj"})
        std::filesystem::copy_file(dir.file(std::string("volcano") + ext), other.file(std::string("volcano") + ext));
    const std::string moved = other.file("volcano.asc");
    std::filesystem::last_write_time(moved, std::filesystem::last_write_time(volcano));  // as cp -p copies
    std::filesystem::copy_file(terrain_cache_path(volcano, cache.path.string()), moved + ".lod");
    EXPECT_FALSE(known_terrain_key(moved));
    Log log;
    log.verbose = true;
    testing::internal::CaptureStderr();
    open_stored_terrain(moved, log);
    const std::string said = testing::internal::GetCapturedStderr();
    EXPECT_EQ(said.rfind("penink: terrain: using cached " + moved + ".lod", 0), 0u) << said;
    const std::optional<TerrainCacheKey> recorded = known_terrain_key(moved);  // hashed once
    ASSERT_TRUE(recorded);
    EXPECT_EQ(recorded->identity, dem_file_identity(moved));
    EXPECT_EQ(recorded->content_hash, rebuilt.key.content_hash);
    EXPECT_TRUE(open_stored_terrain(moved, Log{}).key == *recorded);
    // a link to the DEM (its ctime moves): hashed once, then known again
    std::filesystem::create_hard_link(moved, other.file("link.asc"));
    EXPECT_FALSE(known_terrain_key(moved));
    open_stored_terrain(moved, Log{});
    EXPECT_TRUE(known_terrain_key(moved));
    // a cache beside the DEM that the render does not keep (its caches go to another folder, as
    // where penink is installed): read, its identity not written
    std::filesystem::create_hard_link(moved, other.file("link2.asc"));
    test::TempDir elsewhere("stored_terrain_identity_elsewhere");
    const auto written = std::filesystem::last_write_time(moved + ".lod");
    EXPECT_TRUE(open_stored_terrain(moved, Log{}, elsewhere.path.string()).key == *recorded);
    EXPECT_FALSE(known_terrain_key(moved));
    EXPECT_EQ(std::filesystem::last_write_time(moved + ".lod"), written);
}

// The recorded key is read from the cache's first bytes alone (not its header's checksum): a
// damaged content hash there, with the DEM's identity intact, names the cache, which then fails
// its header's checksum and is built again under the DEM's hashed key, never the damaged one.
TEST(StoredTerrainBuild, ADamagedRecordedKeyIsNeverBuiltUnder) {
    test::TempDir dir, cache("stored_terrain_damaged_key_cache");
    const std::string volcano = copy_volcano(dir);
    const TerrainCacheKey real = open_stored_terrain(volcano, Log{}, cache.path.string()).key;
    const std::string lod = terrain_cache_path(volcano, cache.path.string());
    {
        std::fstream f(lod, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(16 + 16);  // the key's content hash (terrain_cache.hpp)
        f.put('\x5a');
    }
    const std::optional<TerrainCacheKey> damaged = known_terrain_key(volcano, cache.path.string());
    ASSERT_TRUE(damaged);  // the identity still matches
    EXPECT_NE(damaged->content_hash, real.content_hash);
    const StoredTerrain rebuilt = open_stored_terrain(volcano, Log{}, cache.path.string());
    EXPECT_TRUE(rebuilt.key == real);
    const std::optional<TerrainCacheKey> now = recorded_terrain_key(lod);
    ASSERT_TRUE(now);
    EXPECT_EQ(now->content_hash, real.content_hash);
    EXPECT_EQ(now->identity, real.identity);
}
