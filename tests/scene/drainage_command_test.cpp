// `penink drainage` on volcano.asc at the DEM's own resolution: the .dv file and the four
// GeoTIFFs, georeferenced like the DEM, with consistent contents; the routing reaches the file;
// with the default options the file is the cache the render path reads (same file, not
// rewritten) at any vertical exaggeration.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include "scene/drainage_command.hpp"
#include "scene/scene_overrides.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"
#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/stored_creases.hpp"
#include "drainage/drainage_memory.hpp"
#include "scene/cache_build_estimate.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

template <class T> std::vector<T> read_band(const fs::path& p, GDALDataType type, int& w, int& h,
                                            double* gt) {
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(p.string().c_str(), GA_ReadOnly));
    if (!ds) return {};
    w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
    ds->GetGeoTransform(gt);
    std::vector<T> v(std::size_t(w) * h);
    if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, v.data(), w, h, type, 0, 0) != CE_None)
        v.clear();
    GDALClose(ds);
    return v;
}

TEST(DrainageCommand, VolcanoRastersAndDatabase) {
    const fs::path d = fs::temp_directory_path() / ("penink_dcmd_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "volcano.asc");
    if (fs::exists(PENINK_SOURCE_DIR "/examples/volcano.prj"))
        fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", d / "volcano.prj");
    DrainageCommand cmd;
    cmd.dem = (d / "volcano.asc").string();
    cmd.resample = 1;
    cmd.rasters_dir = (d / "rasters").string();
    std::ostringstream log;
    ASSERT_EQ(run_drainage_command(cmd, log), 0) << log.str();
    const DrainageDb db = read_drainage_db(cmd.dem + ".dv");
    EXPECT_EQ(db.cols, 61);
    EXPECT_EQ(db.rows, 87);
    EXPECT_EQ(db.fingerprint.resample, 1u);
    {  // the streamed file (grid positions) reads back to the database a render builds in memory
        DrainageOptions o;
        o.resample = 1;
        DrainageDb built = build_drainage_db(read_dem(cmd.dem), o);
        built.fingerprint = db.fingerprint;
        // the file holds the creases' source (crease_source.hpp), which builds the same creases
        ASSERT_TRUE(db.creases.lines.empty());
        const DrapedLineSet creases = StoredCreases(db.crease_source).lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f));
        EXPECT_TRUE(creases.lines == built.creases.lines);
        EXPECT_TRUE(creases.vertices == built.creases.vertices);
        DrainageDb read = db;
        read.crease_source.clear(), read.creases = built.creases;
        EXPECT_TRUE(read == built);
    }

    GDALAllRegister();
    int w = 0, h = 0;
    double gt[6];
    const auto dir = read_band<std::uint8_t>(d / "rasters/flow_direction.tif", GDT_Byte, w, h, gt);
    ASSERT_EQ(w, 61);
    ASSERT_EQ(h, 87);
    EXPECT_DOUBLE_EQ(gt[1], 10.0);
    EXPECT_DOUBLE_EQ(gt[5], -10.0);
    const std::set<int> codes{0, 1, 2, 4, 8, 16, 32, 64, 128};
    for (std::uint8_t c : dir) EXPECT_TRUE(codes.count(c)) << int(c);
    const auto acc = read_band<std::uint32_t>(d / "rasters/accumulation.tif", GDT_UInt32, w, h, gt);
    const auto basin = read_band<std::uint32_t>(d / "rasters/basin.tif", GDT_UInt32, w, h, gt);
    const auto order = read_band<std::uint8_t>(d / "rasters/stream_order.tif", GDT_Byte, w, h, gt);
    ASSERT_EQ(acc.size(), 61u * 87u);
    ASSERT_EQ(basin.size(), acc.size());
    ASSERT_EQ(order.size(), acc.size());
    std::uint64_t at_outlets = 0;
    for (std::size_t i = 0; i < dir.size(); ++i) {
        if (dir[i] == 0) at_outlets += acc[i];
        EXPECT_GE(order[i], 1);
        EXPECT_GE(basin[i], 1u);
    }
    EXPECT_EQ(at_outlets, 61u * 87u);  // every point drains to exactly one outlet
    // one vertex per point plus one per branch ending at a junction
    std::size_t ends = 0;
    for (const DvBranch& b : db.branches) ends += b.downstream >= 0;
    EXPECT_EQ(db.vertices.size(), 61u * 87u + ends);
    fs::remove_all(d);
}

TEST(DrainageCommand, WritesTheCacheTheRenderPathReads) {
    const fs::path d = fs::temp_directory_path() / ("penink_dcache_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", d / "volcano.prj");
    DrainageCommand cmd;
    cmd.dem = (d / "volcano.asc").string();  // default options, as render uses
    cmd.quiet = true;
    std::ostringstream out;
    ASSERT_EQ(run_drainage_command(cmd, out), 0) << out.str();
    const std::string cache = drainage_cache_path(cmd.dem);
    ASSERT_EQ(cache, cmd.dem + ".dv");
    // and the terrain cache render maps (scene/terrain_view.hpp), valid for this DEM
    ASSERT_EQ(terrain_cache_path(cmd.dem), cmd.dem + ".lod");
    std::string why;
    EXPECT_TRUE(read_terrain_cache(cmd.dem + ".lod", terrain_cache_key(cmd.dem), &why)) << why;
    struct stat before{};
    ASSERT_EQ(::stat(cache.c_str(), &before), 0);
    for (double e : {1.0, 2.5}) {
        DemOptions o;
        o.vertical_exaggeration = e;
        std::vector<std::string> log;
        const DrainageDb db = load_or_build_drainage(cmd.dem, read_dem(cmd.dem, o), DrainageOptions{},
                                                     [&](const std::string& m) { log.push_back(m); });
        ASSERT_EQ(log.size(), 1u) << e;
        EXPECT_EQ(log[0], "drainage: using cached " + cache_file_report(cache)) << e;
        EXPECT_TRUE(db.creases.lines.empty());  // built by the frames from their source
        const DrapedLineSet creases = StoredCreases(db.crease_source).lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f));
        EXPECT_GT(creases.vertices.size(), 100000u);
        struct stat after{};
        ASSERT_EQ(::stat(cache.c_str(), &after), 0);
        EXPECT_EQ(after.st_ino, before.st_ino) << e;  // not rewritten
        EXPECT_EQ(after.st_mtim.tv_sec, before.st_mtim.tv_sec) << e;
        EXPECT_EQ(after.st_mtim.tv_nsec, before.st_mtim.tv_nsec) << e;
    }
    fs::remove_all(d);
}

TEST(DrainageCommand, MissingDemIsBadInput) {
    DrainageCommand cmd;
    cmd.dem = "/nonexistent/dem.tif";
    std::ostringstream log;
    EXPECT_EQ(run_drainage_command(cmd, log), 2);
    EXPECT_EQ(log.str(), "penink: input: /nonexistent/dem.tif: no such file\n");
}

TEST(DrainageCommand, RoutingReachesTheFingerprint) {
    const fs::path d = fs::temp_directory_path() / ("penink_lcr_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "volcano.asc");
    DrainageCommand cmd;
    cmd.dem = (d / "volcano.asc").string();
    cmd.resample = 1;
    cmd.quiet = true;
    std::ostringstream log;
    cmd.output = (d / "pf.dv").string();
    ASSERT_EQ(run_drainage_command(cmd, log), 0) << log.str();
    cmd.routing = DrainageRouting::least_cost;
    cmd.output = (d / "lc.dv").string();
    ASSERT_EQ(run_drainage_command(cmd, log), 0) << log.str();
    const DrainageDb pf_db = read_drainage_db((d / "pf.dv").string());
    const DrainageDb lc_db = read_drainage_db((d / "lc.dv").string());
    EXPECT_EQ(pf_db.fingerprint.routing, 0u);
    EXPECT_EQ(lc_db.fingerprint.routing, 1u);
    EXPECT_NE(pf_db.branches.size(), lc_db.branches.size());
    DrainageFingerprint expected = pf_db.fingerprint;
    expected.routing = 1;
    EXPECT_TRUE(lc_db.fingerprint == expected);  // the routing is all that differs
    fs::remove_all(d);
}

}  // namespace
}  // namespace penink

namespace penink {
namespace {

// The bytes of a file ("" when it cannot be read).
std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A folder of its own holding volcano.asc and its .prj.
fs::path volcano_folder(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("penink_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", d / "volcano.prj");
    return d;
}

}  // namespace

// The render's caches: the terrain cache is built beside the drainage database where the memory
// budget holds both builds, after it where it holds the drainage build alone (a budget of the
// drainage estimate plus a megabyte, under the two: the terrain cache's estimate is more); the
// same two files either way.
TEST(DrainageCommand, TerrainCacheBesideOrAfterTheDrainageIsTheSameFile) {
    std::string dv[2], lod[2];
    const fs::path d = volcano_folder("dbeside");  // one DEM path: the caches name it
    for (const bool after : {false, true}) {
        fs::remove(d / "volcano.asc.dv"), fs::remove(d / "volcano.asc.lod");
        DrainageCommand cmd;
        cmd.dem = (d / "volcano.asc").string();
        cmd.quiet = true;
        if (after) {
            const DemSize size = read_dem_size(cmd.dem);
            const int factor = drainage_factor_for(size.cols, size.rows, 0);
            cmd.max_memory = std::uint64_t(drainage_build_bytes(size.cols, size.rows, factor)) + (1u << 20);
            ASSERT_LT(double(cmd.max_memory),
                      drainage_build_bytes(size.cols, size.rows, factor) + terrain_cache_estimate(size.cols, size.rows).peak_bytes);
        }
        std::ostringstream log;
        ASSERT_EQ(run_drainage_command(cmd, log), 0) << log.str();
        dv[after] = file_bytes(cmd.dem + ".dv"), lod[after] = file_bytes(cmd.dem + ".lod");
        EXPECT_GT(dv[after].size(), 1000u);
        EXPECT_GT(lod[after].size(), 1000u);
    }
    fs::remove_all(d);
    EXPECT_TRUE(dv[0] == dv[1]);
    EXPECT_TRUE(lod[0] == lod[1]);
}

// A drainage command that fails once both builds have started (its rasters' folder is a file)
// leaves neither cache: the terrain cache built beside it is removed; one there before is kept.
TEST(DrainageCommand, AFailedBuildLeavesNoTerrainCacheOfItsOwn) {
    const fs::path d = volcano_folder("dfail");
    DrainageCommand cmd;
    cmd.dem = (d / "volcano.asc").string();
    cmd.quiet = true;
    cmd.rasters_dir = (d / "rasters").string();
    std::ofstream(cmd.rasters_dir) << "not a folder";
    std::ostringstream log;
    EXPECT_EQ(run_drainage_command(cmd, log), 2);
    EXPECT_NE(log.str().find("rasters"), std::string::npos) << log.str();
    EXPECT_FALSE(fs::exists(cmd.dem + ".dv"));
    EXPECT_FALSE(fs::exists(cmd.dem + ".lod"));
    // a terrain cache there before the command stays
    DrainageCommand ok;
    ok.dem = cmd.dem, ok.quiet = true;
    ASSERT_EQ(run_drainage_command(ok, log), 0) << log.str();
    fs::remove(cmd.dem + ".dv");
    const std::string before = file_bytes(cmd.dem + ".lod");
    ASSERT_GT(before.size(), 1000u);
    EXPECT_EQ(run_drainage_command(cmd, log), 2);
    EXPECT_EQ(file_bytes(cmd.dem + ".lod"), before);
    EXPECT_FALSE(fs::exists(cmd.dem + ".dv"));
    fs::remove_all(d);
}

}  // namespace penink

namespace penink {
namespace {

std::map<std::string, std::string> folder_bytes(const fs::path& d) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::directory_iterator(d)) files[e.path().filename().string()] = file_bytes(e.path());
    return files;
}

Scene default_scene(const std::string& dem) {
    SceneOverrides o;
    o.input = dem;
    return load_scene_with_overrides(o);
}

}  // namespace

// With the render's options, the command also writes the crease tiles of the whole view that a
// render of the DEM with the default scene reads: the files that render would write itself, so
// that it writes none. With another factor it writes none (the render would build its own
// database).
TEST(DrainageCommand, WritesTheCreaseTilesTheFirstRenderReads) {
    const fs::path a = volcano_folder("dtiles_a"), b = volcano_folder("dtiles_b");
    DrainageCommand cmd;
    cmd.dem = (a / "volcano.asc").string();
    std::ostringstream log;
    ASSERT_EQ(run_drainage_command(cmd, log), 0) << log.str();
    const fs::path tiles = crease_tile_folder(cmd.dem + ".dv");
    ASSERT_TRUE(fs::is_directory(tiles)) << log.str();
    const std::map<std::string, std::string> written = folder_bytes(tiles);
    ASSERT_GT(written.size(), 4u);
    EXPECT_NE(log.str().find("drainage: crease tiles of the whole view: " + std::to_string(written.size()) + " files in " +
                             tiles.string()),
              std::string::npos)
        << log.str();
    Scene scene = default_scene(cmd.dem);
    EXPECT_EQ(write_view_crease_tiles(scene, Log{}), 0u) << "the first render writes none";
    EXPECT_EQ(folder_bytes(tiles), written);
    // the same DEM elsewhere, its tiles left to the render: the same files
    DrainageCommand other = cmd;
    other.dem = (b / "volcano.asc").string(), other.quiet = true;
    ASSERT_EQ(run_drainage_command(other, log), 0) << log.str();
    fs::remove_all(crease_tile_folder(other.dem + ".dv"));
    Scene scene_b = default_scene(other.dem);
    EXPECT_EQ(write_view_crease_tiles(scene_b, Log{}), written.size());
    EXPECT_EQ(folder_bytes(crease_tile_folder(other.dem + ".dv")), written);
    // another factor: no tiles
    fs::remove_all(b);
    fs::create_directories(b);
    fs::copy_file(a / "volcano.asc", b / "volcano.asc"), fs::copy_file(a / "volcano.prj", b / "volcano.prj");
    other.resample = 3;
    ASSERT_EQ(run_drainage_command(other, log), 0) << log.str();
    EXPECT_FALSE(fs::exists(crease_tile_folder(other.dem + ".dv")));
    fs::remove_all(a), fs::remove_all(b);
}

}  // namespace penink
