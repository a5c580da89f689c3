// The cache build estimate: the terrain cache's disk is of the order of the file written (its
// coded size follows the DEM's roughness; noise codes to a few times the estimate); time and memory reproduce the measurements they were fitted to (jacksboro
// refined 5, 10 and 29 times: 2015x1720, 4030x3440 and 11687x9976 nodes) and grow with the DEM;
// the line printed.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "scene/cache_build_estimate.hpp"
#include "surface/terrain_cache.hpp"
#include "support/synthetic_terrain.hpp"
#include "support/temp_dir.hpp"

using namespace penink;

TEST(CacheBuildEstimate, TerrainDiskIsOfTheOrderOfTheFileWritten) {
    test::TempDir dir;
    const StoredTerrain t = store_terrain(terrain_from_function(300, 257, 5.0, rough_hills));
    write_terrain_cache(dir.file("h.lod"), t, {1, 2, 3, 0, true});
    const double file = double(std::filesystem::file_size(dir.file("h.lod")));
    const double want = terrain_cache_estimate(300, 257).disk_bytes;
    EXPECT_LE(want, file);      // rough_hills: noise at the cell scale, coded larger than a real DEM
    EXPECT_LE(file, 6.0 * want);  // 5.6 times here (6.5 bytes a node against 1.17)
}

TEST(CacheBuildEstimate, ReproducesTheMeasurementsItWasFittedTo) {
    // penink drainage DEM -o x.dv on jacksboro refined 10 and 29 times (/usr/bin/time: wall,
    // maximum resident KiB as bytes)
    const CacheBuildEstimate d10 = drainage_cache_estimate(4030, 3440), d29 = drainage_cache_estimate(11687, 9976);
    EXPECT_NEAR(d10.seconds, 3.25, 0.05);
    EXPECT_NEAR(d29.seconds, 42.6, 0.5);
    EXPECT_NEAR(d10.peak_bytes, 571.5e6, 5e6);
    EXPECT_NEAR(d29.peak_bytes, 2961.8e6, 20e6);
    EXPECT_NEAR(d10.disk_bytes, 25.5e6, 0.3e6);  // the .dv written
    EXPECT_NEAR(d29.disk_bytes, 213.1e6, 2e6);
    const CacheBuildEstimate t5 = terrain_cache_estimate(2015, 1720), t10 = terrain_cache_estimate(4030, 3440);
    EXPECT_NEAR(t10.seconds, 2.3, 0.01);
    // the build alone: PENINK_BENCH_DEM=DEM /usr/bin/time -v build/terrain_cache_build_bench
    EXPECT_GE(t5.peak_bytes, 103.4e6);  // the base fitted to the larger two: about 27 MB over
    EXPECT_LE(t5.peak_bytes, 145e6);
    EXPECT_NEAR(t10.peak_bytes, 172.5e6, 4e6);  // 169.3: the lattice's share fitted to x29 alone
    EXPECT_NEAR(terrain_cache_estimate(11687, 9976).peak_bytes, 504.7e6, 5e6);
    // a DEM's cache in bounded memory: a billion cells' (jacksboro refined 85 times, a padded
    // square of 65537^2 nodes) in 4 GB
    EXPECT_LT(terrain_cache_estimate(34255, 29240).peak_bytes, 4e9);
    EXPECT_NEAR(t10.disk_bytes, 18.7e6, 0.1e6);  // the .lod written
    // a 1/3 arc-second NED tile, 10812 x 10812 nodes: 0.16 GB of terrain cache
    const CacheBuildEstimate ned = terrain_cache_estimate(10812, 10812);
    EXPECT_NEAR(ned.disk_bytes, 0.158e9, 0.01e9);
    EXPECT_GT(drainage_cache_estimate(10812, 10812).seconds, 8.0 * d10.seconds);  // superlinear
}

TEST(CacheBuildEstimate, OneLine) {
    CacheBuildEstimate e;
    e.seconds = 164.6, e.peak_bytes = 9.76e9, e.disk_bytes = 6.54e9;
    EXPECT_EQ(describe_cache_estimate("drainage", "drainage database", 10812, 10812, e),
              "penink: drainage: building the drainage database of a 10812x10812 DEM (116.9 M cells): about 165 s, "
              "9.8 GB of memory at peak, 6.5 GB on disk (estimate)");
    e.seconds = 2.3, e.peak_bytes = 0.66e9, e.disk_bytes = 26.7e6;  // under a gigabyte: megabytes
    EXPECT_EQ(describe_cache_estimate("terrain", "terrain cache", 4030, 3440, e),
              "penink: terrain: building the terrain cache of a 4030x3440 DEM (13.9 M cells): about 2 s, "
              "0.7 GB of memory at peak, 27 MB on disk (estimate)");
}

TEST(CacheBuildEstimate, AnnouncedAboveTenMillionCellsOnly) {
    std::ostringstream small, large, terrain;
    announce_cache_build(small, CacheKind::drainage, 3001, 3001);  // 9.0 M cells: no line
    EXPECT_EQ(small.str(), "");
    announce_cache_build(large, CacheKind::drainage, 4030, 3440);
    EXPECT_EQ(large.str(), describe_cache_estimate("drainage", "drainage database", 4030, 3440,
                                                   drainage_cache_estimate(4030, 3440)) + "\n");
    announce_cache_build(terrain, CacheKind::terrain, 4030, 3440);
    EXPECT_EQ(terrain.str(), describe_cache_estimate("terrain", "terrain cache", 4030, 3440,
                                                     terrain_cache_estimate(4030, 3440)) + "\n");
}
