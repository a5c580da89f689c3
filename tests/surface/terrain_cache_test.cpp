// The terrain cache: what is written is what is read back (nodes, pyramid, georeference), a
// frame selected from the file is the frame selected in memory, at any exaggeration; a stale,
// damaged header, truncated, missing or not regular (FIFO, folder) file is refused with its
// reason; damage in any block of the arrays (flipped, zeroed, NaN) is found when that block is
// read; a frame of a small view reads a small part of a large cache, and damage outside what it
// reads does not touch it; an unwritable place is an Error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

#include <sys/stat.h>
#include <filesystem>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.hpp"
#include "core/checked_blocks.hpp"
#include "core/error.hpp"
#include "input/dem_reader.hpp"
#include "input/geographic_nodes.hpp"
#include "surface/terrain_cache.hpp"
#include "support/synthetic_terrain.hpp"
#include "support/temp_dir.hpp"
#include "support/test_grids.hpp"

using namespace penink;

namespace {

// 300 x 257 nodes, 5 m, with a nodata hole, georeferenced like a UTM DEM.
Terrain hills() {
    Terrain t = terrain_from_function(300, 257, 5.0, rough_hills);
    for (int r = 100; r < 120; ++r)
        for (int c = 40; c < 70; ++c) t.valid[t.index(c, r)] = 0;
    t.origin = {512345.0, 4012345.0};
    t.crs_wkt = "PROJCS[\"WGS 84 / UTM zone 16N\"]";
    t.utm_zone = 16;
    t.geotransform = {512000.0, 5.0, 0.0, 4013000.0, 0.0, -5.0};
    t.xy_unit = 1.0;
    t.source = "hills.tif";
    return t;
}

TerrainCacheKey key() { return {123456, 789, 0xabcdef, 0, true}; }

Camera oblique(const StoredTerrain& t, double e) {
    return frame_box(glm::dvec3(t.plan_lo, t.lod.z_min * e), glm::dvec3(t.plan_hi, t.lod.z_max * e),
                     {.azimuth = 30.0, .altitude = -20.0, .fov = 40.0, .width = 800, .height = 600});
}

void expect_same_mesh(const SurfaceMesh& a, const SurfaceMesh& b) {
    ASSERT_EQ(a.tri.size(), b.tri.size());
    ASSERT_EQ(a.pos.size(), b.pos.size());
    for (std::size_t i = 0; i < a.tri.size(); ++i) ASSERT_EQ(a.tri[i], b.tri[i]);
    for (std::size_t i = 0; i < a.pos.size(); ++i) {
        ASSERT_EQ(a.pos[i], b.pos[i]);
        ASSERT_EQ(a.normal[i], b.normal[i]);
    }
}

}  // namespace

TEST(TerrainCache, RoundTripMapsWhatWasWritten) {
    test::TempDir dir;
    const Terrain flat = hills();
    const StoredTerrain mem = store_terrain(flat);
    ASSERT_NE(mem.in_memory, nullptr);
    const std::string path = dir.file("hills.lod");
    write_terrain_cache(path, mem, key());
    std::string why;
    const std::optional<StoredTerrain> map = read_terrain_cache(path, key(), &why);
    ASSERT_TRUE(map) << why;
    EXPECT_EQ(map->in_memory, nullptr);
    ASSERT_NE(map->nodes.blocks, nullptr);
    EXPECT_EQ(map->nodes.blocks->bytes_read(), 0u) << "opening reads the header alone";
    read_whole(*map);
    // every block once, but the whole blocks of valid flags alone: known by their checksums
    // (blocks of 256 elements, terrain_cache.hpp)
    std::uint64_t all_valid = 0;
    for (std::size_t b = 0; (b + 1) * 256 <= flat.valid.size(); ++b)
        all_valid += std::all_of(flat.valid.begin() + std::ptrdiff_t(b * 256), flat.valid.begin() + std::ptrdiff_t((b + 1) * 256),
                                 [](std::uint8_t v) { return v == 1; });
    ASSERT_GT(all_valid, 0u);
    EXPECT_EQ(map->nodes.blocks->blocks_read() + all_valid, map->nodes.blocks->block_count());
    EXPECT_LT(map->nodes.blocks->bytes_read(), map->nodes.blocks->bytes());
    const std::uint64_t read = map->nodes.blocks->bytes_read();
    read_whole(*map);
    EXPECT_EQ(map->nodes.blocks->bytes_read(), read) << "each block once";
    EXPECT_EQ(map->meta.cols, 300);
    EXPECT_EQ(map->meta.rows, 257);
    EXPECT_EQ(map->meta.origin, flat.origin);
    EXPECT_EQ(map->meta.crs_wkt, flat.crs_wkt);
    EXPECT_EQ(map->meta.utm_zone, 16);
    EXPECT_EQ(map->meta.geotransform, flat.geotransform);
    EXPECT_EQ(map->meta.xy_unit, 1.0);
    EXPECT_EQ(map->meta.elevation_min, flat.elevation_min);
    EXPECT_EQ(map->meta.elevation_max, flat.elevation_max);
    EXPECT_TRUE(map->meta.pos.empty());
    EXPECT_EQ(map->plan_lo, mem.plan_lo);
    EXPECT_EQ(map->plan_hi, mem.plan_hi);
    EXPECT_DOUBLE_EQ(map->plan_lo.x, -747.5);  // 300 nodes 5 m apart, centred
    ASSERT_EQ(map->nodes.size(), flat.size());
    for (std::size_t i = 0; i < flat.size(); ++i) {
        ASSERT_EQ(map->nodes.pos[i], flat.pos[i]);
        ASSERT_EQ(map->nodes.valid[i], flat.valid[i]);
    }
    EXPECT_EQ(map->lod.levels, mem.lod.levels);
    EXPECT_EQ(map->lod.lipschitz, mem.lod.lipschitz);
    EXPECT_EQ(map->lod.z_min, mem.lod.z_min);
    EXPECT_EQ(map->lod.z_max, mem.lod.z_max);
    ASSERT_EQ(map->lod.error.size(), mem.lod.error.size());
    EXPECT_TRUE(std::equal(map->lod.error.begin(), map->lod.error.end(), mem.lod.error.begin(),
                           [](float a, float b) { return a == b || (std::isinf(a) && std::isinf(b)); }));
}

// The cache is independent of the exaggeration: one file draws every one, as memory does.
TEST(TerrainCache, MappedFramesEqualFramesInMemoryAtAnyExaggeration) {
    test::TempDir dir;
    const StoredTerrain mem = store_terrain(hills());
    write_terrain_cache(dir.file("h.lod"), mem, key());
    const std::optional<StoredTerrain> map = read_terrain_cache(dir.file("h.lod"), key());
    ASSERT_TRUE(map);
    for (const double e : {1.0, 3.0}) {
        const Camera cam = oblique(mem, e);
        LodOptions o;
        LodSelection a, b;
        const SurfaceMesh from_mem = select_lod_mesh(mem.lod, mem.drawn(e), e, cam, o, &a);
        const SurfaceMesh from_map = select_lod_mesh(map->lod, map->drawn(e), e, cam, o, &b);
        EXPECT_GT(a.triangles, 1000u);
        expect_same_mesh(from_mem, from_map);
        // drawn at e: z = float(double(z) * e), as the DEM reader computes exaggerated heights
        const std::size_t i = mem.nodes.index(150, 128);
        EXPECT_EQ(map->drawn(e).at(i).z, float(double(mem.in_memory->pos[i].z) * e));
    }
}

TEST(TerrainCache, RefusesStaleDamagedTruncatedAndMissingFiles) {
    test::TempDir dir;
    const StoredTerrain mem = store_terrain(hills());
    const std::string path = dir.file("h.lod");
    write_terrain_cache(path, mem, key());
    std::string why;
    TerrainCacheKey other = key();
    other.mtime_ns += 1;
    EXPECT_FALSE(read_terrain_cache(path, other, &why));
    EXPECT_EQ(why, "terrain cache is stale (DEM changed)");
    other = key(), other.utm_zone = 17;
    EXPECT_FALSE(read_terrain_cache(path, other, &why));
    EXPECT_EQ(why, "terrain cache is stale (DEM changed)");

    std::vector<char> bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto write = [&](const std::vector<char>& b) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(b.data(), std::streamsize(b.size()));
    };
    std::vector<char> damaged = bytes;
    damaged[60] ^= 1;  // a grid field
    write(damaged);
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "damaged terrain cache (header checksum)");
    write(std::vector<char>(bytes.begin(), bytes.end() - 4));
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "damaged terrain cache (lengths)");
    write(std::vector<char>(bytes.begin(), bytes.begin() + 20));
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "truncated terrain cache");
    write(std::vector<char>(bytes.begin(), bytes.begin() + 100));
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "damaged terrain cache (header length)");
    damaged = bytes;
    damaged[8] = char(terrain_cache_version - 1);  // version
    write(damaged);
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "terrain cache of another version");
    damaged = bytes;
    damaged[0] = 'X';
    write(damaged);
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "not a terrain cache (bad magic)");
    EXPECT_FALSE(read_terrain_cache(dir.file("none.lod"), key(), &why));
    EXPECT_EQ(why, "no terrain cache");
    write(bytes);
    EXPECT_TRUE(read_terrain_cache(path, key(), &why));
    // the identity alone is outside the header's checksum: written in place, the cache still reads
    EXPECT_TRUE(record_terrain_identity(path, 0x0123456789abcdefull));
    const std::optional<TerrainCacheKey> recorded = recorded_terrain_key(path);
    ASSERT_TRUE(recorded);
    EXPECT_EQ(recorded->identity, 0x0123456789abcdefull);
    EXPECT_TRUE(*recorded == key());
    EXPECT_TRUE(read_terrain_cache(path, key(), &why)) << why;
    EXPECT_EQ(std::filesystem::file_size(path), bytes.size());
    damaged = bytes;
    damaged[16 + 32 - 1] ^= 1;  // the byte before it (the key's north flag): under the checksum
    write(damaged);
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    // not a cache of this version, or none: nothing written
    damaged = bytes;
    damaged[8] = char(terrain_cache_version - 1);
    write(damaged);
    EXPECT_FALSE(record_terrain_identity(path, 7));
    {
        std::ifstream in(path, std::ios::binary);
        EXPECT_TRUE(std::vector<char>(std::istreambuf_iterator<char>(in), {}) == damaged);
    }
    EXPECT_FALSE(record_terrain_identity(dir.file("none.lod"), 7));
    EXPECT_FALSE(std::filesystem::exists(dir.file("none.lod")));
}

TEST(TerrainCache, UnwritablePlaceIsAnErrorAndLeavesNothing) {
    test::TempDir dir;
    const StoredTerrain mem = store_terrain(hills());
    const std::string path = dir.file("missing/h.lod");
    try {
        write_terrain_cache(path, mem, key());
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: surface: " + path + ": cannot write terrain cache: No such file or directory");
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

TEST(TerrainCache, StoreTerrainNeedsUnexaggeratedHeights) {
    Terrain t = hills();
    t.vertical_exaggeration = 2.0;
    EXPECT_THROW(store_terrain(t), std::invalid_argument);
}

namespace {

std::vector<char> file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void put_bytes(const std::string& path, const std::vector<char>& b) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(b.data(), std::streamsize(b.size()));
}

}  // namespace

// Every block of the arrays carries its checksum: damage anywhere in them (the first node, the
// middle of the nodes, the last pyramid entry) is found as the block is read, whatever
// the damage (one bit, a zeroed run, NaN or huge floats written over good ones); the file opens
// (its header is sound) and reading the damaged block throws. A block of valid flags alone (the
// middle of the flags) is known by its checksum and never read: damage there changes nothing read.
// A cut is found at the open.
TEST(TerrainCache, DamageInAnyBlockOfTheArraysIsFoundWhenRead) {
    test::TempDir dir;
    const StoredTerrain mem = store_terrain(hills());
    const std::string path = dir.file("h.lod");
    write_terrain_cache(path, mem, key());
    const std::vector<char> bytes = file_bytes(path);
    ASSERT_TRUE(read_terrain_cache(path, key()));
    // array offsets: the coded arrays follow the header: pos, then valid, then error
    std::uint64_t at[3];
    // prefix 16, key 40, grid 16 + 16 + 48 + 24 + 8 + 16, pyramid 16 + 32 bytes (terrain_cache.hpp)
    std::memcpy(at, bytes.data() + 16 + 40 + 16 + 16 + 48 + 24 + 8 + 16 + 16 + 32, 24);
    std::uint32_t header = 0;
    std::memcpy(&header, bytes.data() + 12, 4);
    ASSERT_EQ(at[0], header);  // the offsets were read right
    ASSERT_LT(at[0], at[1]);
    ASSERT_LT(at[1], at[2]);
    // the first node block, one amid the nodes, one amid the flags, the last pyramid block
    const std::size_t offsets[] = {std::size_t(at[0]), std::size_t((at[0] + at[1]) / 2), bytes.size() - 4};
    std::string why;
    int damaged = 0;
    auto expect_refused = [&](const std::vector<char>& b) {
        if (b == bytes) return;  // the damage wrote what was there (a zero over a zero)
        ++damaged;
        put_bytes(path, b);
        const std::optional<StoredTerrain> opened = read_terrain_cache(path, key(), &why);
        ASSERT_TRUE(opened) << why;
        try {
            read_whole(*opened);
            ADD_FAILURE() << "damage not found";
        } catch (const DamagedBlockError& e) {
            EXPECT_EQ(e.file(), path);
            EXPECT_NE(std::string(e.what()).find("checksum mismatch in block"), std::string::npos) << e.what();
        }
    };
    for (const std::size_t o : offsets) {
        SCOPED_TRACE(o);
        std::vector<char> b = bytes;
        b[o] ^= 1;  // one bit
        expect_refused(b);
        b = bytes;
        std::fill(b.begin() + std::ptrdiff_t(o), b.begin() + std::ptrdiff_t(std::min(o + 64, b.size())), 0);
        expect_refused(b);
        for (const float v : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 3e38f}) {
            b = bytes;
            std::memcpy(b.data() + o, &v, 4);
            expect_refused(b);
        }
    }
    EXPECT_GE(damaged, 13);  // of 15: at most the last entry's zeroing and its infinity may change nothing
    {  // amid the flags: a block of valid nodes alone, taken as its checksum says
        std::vector<char> b = bytes;
        const std::size_t o = std::size_t((at[1] + at[2]) / 2);
        std::fill(b.begin() + std::ptrdiff_t(o), b.begin() + std::ptrdiff_t(o + 64), 0);
        ASSERT_NE(b, bytes);
        put_bytes(path, b);
        const std::optional<StoredTerrain> opened = read_terrain_cache(path, key(), &why);
        ASSERT_TRUE(opened) << why;
        read_whole(*opened);
        EXPECT_EQ(std::memcmp(opened->nodes.valid, mem.nodes.valid, mem.nodes.size()), 0);
    }
    // cut in the middle of the nodes: the lengths no longer match the file
    put_bytes(path, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(at[0] + 5000)));
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "damaged terrain cache (lengths)");
    put_bytes(path, bytes);
    EXPECT_TRUE(read_terrain_cache(path, key(), &why)) << why;
}

// A FIFO or a folder where the cache would be is not read (a FIFO would block the render).
TEST(TerrainCache, NotARegularFileIsIgnored) {
    test::TempDir dir;
    const std::string fifo = dir.file("fifo.lod");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::string why;
    EXPECT_FALSE(read_terrain_cache(fifo, key(), &why));
    EXPECT_EQ(why, "terrain cache is not a regular file");
    std::filesystem::create_directory(dir.file("dir.lod"));
    EXPECT_FALSE(read_terrain_cache(dir.file("dir.lod"), key(), &why));
    EXPECT_EQ(why, "terrain cache is not a regular file");
}

namespace {

// Flips one bit of the file at `offset`, in place.
void flip_byte(const std::string& path, std::uint64_t offset) {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekg(std::streamoff(offset));
    char c = 0;
    f.get(c);
    f.seekp(std::streamoff(offset));
    f.put(char(c ^ 1));
}

}  // namespace

// A frame of a small part of a large cache reads and checks the blocks its selection touches, a
// small share of the file; damage in a block it does not read leaves the frame as it was, damage
// in one it reads is found (DamagedBlockError) when it is read.
TEST(TerrainCache, SmallViewReadsASmallPartAndOnlyItsDamageCounts) {
    test::TempDir dir;
    const StoredTerrain mem = store_terrain(terrain_from_function(1025, 1025, 5.0, rough_hills));
    const std::string path = dir.file("big.lod");
    write_terrain_cache(path, mem, key());
    const std::uint64_t file_bytes = std::filesystem::file_size(path);
    ASSERT_GT(file_bytes, 1025u * 1025u);  // coded: well under the 17 MB of its floats, still over a byte a node
    // straight down (orthographic) on the 100 x 100 nodes around node (200, 200): 1 % of the DEM
    std::vector<glm::dvec3> corners;
    for (const int c : {150, 250})
        for (const int r : {150, 250}) {
            const glm::vec3 p = mem.nodes.at(c, r);
            corners.emplace_back(p.x, p.y, double(mem.lod.z_min));
            corners.emplace_back(p.x, p.y, double(mem.lod.z_max));
        }
    const Camera cam = frame_points_orthographic(corners, {.azimuth = 0.0, .altitude = -89.0, .width = 400, .height = 300, .view_width = 0.0, .fill = 1.0});
    LodOptions o;
    LodSelection in_memory, from_file;
    const SurfaceMesh want = select_lod_mesh(mem.lod, mem.drawn(1.0), 1.0, cam, o, &in_memory);
    ASSERT_GT(in_memory.triangles, 1000u);
    auto frame = [&](LodSelection* stats) {
        const std::optional<StoredTerrain> map = read_terrain_cache(path, key());
        if (!map) throw std::runtime_error("not opened");
        const SurfaceMesh mesh = select_lod_mesh(map->lod, map->drawn(1.0), 1.0, cam, o, stats);
        return std::make_pair(mesh, map);
    };
    auto [mesh, map] = frame(&from_file);
    expect_same_mesh(want, mesh);
    const CheckedBlocks& blocks = *map->nodes.blocks;
    std::printf("small view: %llu of %llu bytes of the cache read (%llu of %llu blocks)\n",
                (unsigned long long)blocks.bytes_read(), (unsigned long long)file_bytes,
                (unsigned long long)blocks.blocks_read(), (unsigned long long)blocks.block_count());
    EXPECT_LT(blocks.bytes_read() * 8, file_bytes);
    EXPECT_LT(blocks.blocks_read() * 8, blocks.block_count());
    // a block of node positions the frame did not read (the DEM's south-east) and one it read;
    // the selection reads its nodes through a small cache of blocks (NodePointReader), keeping none
    const std::uint64_t unread = map->nodes.index(900, 900), read = map->nodes.index(200, 200);
    ASSERT_FALSE(blocks.has_read(GridNodes::pos_array, unread));
    ASSERT_FALSE(blocks.has_read(GridNodes::pos_array, read));
    flip_byte(path, blocks.file_offset(GridNodes::pos_array, unread));
    {
        LodSelection again;
        const auto [damaged_elsewhere, opened] = frame(&again);
        expect_same_mesh(want, damaged_elsewhere);
    }
    flip_byte(path, blocks.file_offset(GridNodes::pos_array, read));
    try {
        frame(nullptr);
        ADD_FAILURE() << "damage in the view not found";
    } catch (const DamagedBlockError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.stage(), "surface");
    }
}

// A whole view of a large DEM selects a coarse mesh, most of whose nodes lie on the node lattice
// (terrain_lod.hpp): read there, the frame is the same bit for bit, positions, normals and all, and
// it reads fewer blocks than without the lattice (which then reads, for each coarse vertex, the
// blocks of three rows of nodes, and a block of errors for each node tested).
TEST(TerrainCache, WholeViewReadsItsCoarseNodesFromTheLattice) {
    test::TempDir dir;
    Terrain flat = terrain_from_function(2049, 1537, 5.0, rough_hills);
    for (int r = 800; r < 861; ++r)  // a hole: lattice nodes with some neighbours lacking data
        for (int c = 1000; c < 1037; ++c) flat.valid[flat.index(c, r)] = 0;
    const StoredTerrain mem = store_terrain(on_affine_grid(std::move(flat)));
    const std::string path = dir.file("big.lod");
    write_terrain_cache(path, mem, key());
    for (const double e : {1.0, 2.5}) {
        const Camera cam = oblique(mem, e);
        LodOptions o;
        LodSelection s;
        const SurfaceMesh want = select_lod_mesh(mem.lod, mem.drawn(e), e, cam, o, &s);
        ASSERT_GT(s.triangles, 5000u);
        std::uint64_t blocks[2] = {0, 0};
        for (const bool lattice : {true, false}) {
            std::optional<StoredTerrain> map = read_terrain_cache(path, key());
            ASSERT_TRUE(map);
            ASSERT_EQ(map->lod.lattice_step, lod_lattice_step);
            if (!lattice) map->lod.lattice_step = 0;
            expect_same_mesh(want, select_lod_mesh(map->lod, map->drawn(e), e, cam, o));
            blocks[lattice ? 0 : 1] = map->nodes.blocks->blocks_read();
        }
        std::printf("whole view at %.1f: %zu triangles, %llu blocks read with the lattice, %llu without\n", e,
                    s.triangles, (unsigned long long)blocks[0], (unsigned long long)blocks[1]);
        // unexaggerated, a tenth (the mesh coarse); at 2.5 the rough hills refine to finer
        // triangles than the lattice's near the eye, which read their own rows (0.62 of them here)
        EXPECT_LT(blocks[0] * (e == 1.0 ? 4 : 1), blocks[1]);
    }
}

// A sampled grid of every 4th or 8th node from a node of the coarse nodes' lattice (the hachures'
// on a DEM finer than the pixels) is read from the coarse nodes: the positions and flags of the
// nodes themselves, holes included, from fewer blocks (a coarse row's blocks for every step-th
// row's: 0.32 of them at a step of 4 or 8 on rows of 2049 nodes); a step of 2, or a first node off
// that lattice, reads the nodes.
TEST(TerrainCache, SampledNodesAreReadFromTheCoarseNodes) {
    test::TempDir dir;
    Terrain flat = terrain_from_function(2049, 301, 5.0, rough_hills);
    for (int r = 0; r < 40; ++r)
        for (int c = 2000; c < 2049; ++c) flat.valid[flat.index(c, r)] = 0;  // a hole at the north-east edge
    for (int r = 100; r < 130; ++r)
        for (int c = 500; c < 600; ++c) flat.valid[flat.index(c, r)] = 0;
    const StoredTerrain mem = store_terrain(on_affine_grid(std::move(flat)));
    write_terrain_cache(dir.file("h.lod"), mem, key());
    for (const int step : {2, 4, 8}) {
        for (const GridWindow w : {GridWindow{0, 0, 2049, 301}, GridWindow{8, 4, 1950, 281}, GridWindow{3, 0, 2049, 301}}) {
            SCOPED_TRACE(::testing::Message() << "step " << step << " window from " << w.c0 << ", " << w.r0);
            std::uint64_t blocks[2] = {0, 0};
            for (const bool coarse : {true, false}) {
                std::optional<StoredTerrain> map = read_terrain_cache(dir.file("h.lod"), key());
                ASSERT_TRUE(map);
                ASSERT_EQ(map->nodes.coarse_step, grid_coarse_step);
                if (!coarse) map->nodes.coarse_step = 0;
                const SampledWindow sw = sampled_window(map->nodes, w, step);
                const GridWindow part{0, 0, sw.cols, sw.rows};
                std::vector<glm::vec3> got(std::size_t(sw.cols) * std::size_t(sw.rows));
                std::vector<std::uint8_t> got_valid(got.size());
                read_sampled(map->nodes, sw, part, got.data(), got_valid.data());
                for (int j = 0; j < sw.rows; ++j)
                    for (int i = 0; i < sw.cols; ++i) {
                        const std::size_t n = mem.nodes.index(w.c0 + i * step, w.r0 + j * step), o = std::size_t(j * sw.cols + i);
                        ASSERT_EQ(got_valid[o], mem.nodes.valid[n]);
                        ASSERT_EQ(got[o], mem.nodes.pos[n]);
                    }
                blocks[coarse ? 0 : 1] = map->nodes.blocks->blocks_read();
            }
            if (step >= grid_coarse_step && w.c0 % grid_coarse_step == 0 && w.r0 % grid_coarse_step == 0) {
                std::printf("step %d from %d, %d: %llu blocks read from the coarse nodes, %llu from the nodes\n", step,
                            w.c0, w.r0, (unsigned long long)blocks[0], (unsigned long long)blocks[1]);
                EXPECT_LT(blocks[0] * 2, blocks[1]);
            } else {
                EXPECT_EQ(blocks[0], blocks[1]);
            }
        }
    }
}

// The arrays are coded (core/block_codec.hpp): the file is a fraction of the floats it holds (17
// bytes a node of positions, flags and errors; 0.37 and 0.35 of them here, heights at float
// precision either way: a bound of 0.42 leaves room for another deflater's choices), and holds
// exactly the header and the blocks CheckedBlocks reads.
TEST(TerrainCache, CodedFileIsAFractionOfItsFloats) {
    test::TempDir dir;
    for (const bool smooth : {false, true}) {
        SCOPED_TRACE(smooth ? "gaussian hill" : "rough hills");
        const Terrain flat = smooth ? terrain_from_function(300, 257, 5.0, gaussian_hill(300.0, 250.0))
                                    : terrain_from_function(300, 257, 5.0, rough_hills);
        const StoredTerrain mem = store_terrain(flat);
        const std::string path = dir.file(smooth ? "smooth.lod" : "rough.lod");
        write_terrain_cache(path, mem, key());
        const double floats = 13.0 * double(flat.size()) + 4.0 * double(mem.lod.error.size());
        const double file = double(std::filesystem::file_size(path));
        std::printf("%s: %.0f bytes, %.3f of its floats\n", smooth ? "smooth" : "rough", file, file / floats);
        EXPECT_LT(file, 0.42 * floats);
        const std::optional<StoredTerrain> map = read_terrain_cache(path, key());
        ASSERT_TRUE(map);
        std::uint32_t header = 0;
        const std::vector<char> bytes = file_bytes(path);
        std::memcpy(&header, bytes.data() + 12, 4);
        EXPECT_EQ(double(map->nodes.blocks->bytes() + header), file);
    }
}

// The sampled nodes of window w at `step` (sampled_window), read whole, or (tile > 0) a tile of
// tile x tile of them at a time (read_sampled of each, as the hachures read them).
struct Sampled {
    SampledWindow s;
    std::vector<glm::vec3> pos;
    std::vector<std::uint8_t> valid;
};
Sampled sample(const GridNodes& nodes, GridWindow w, int step, int tile = 0) {
    Sampled out;
    out.s = sampled_window(nodes, w, step);
    out.pos.resize(std::size_t(out.s.cols) * std::size_t(out.s.rows)), out.valid.resize(out.pos.size());
    if (tile <= 0) {
        read_sampled(nodes, out.s, GridWindow{0, 0, out.s.cols, out.s.rows}, out.pos.data(), out.valid.data());
        return out;
    }
    std::vector<glm::vec3> pos;
    std::vector<std::uint8_t> valid;
    for (int r0 = 0; r0 < out.s.rows; r0 += tile)
        for (int c0 = 0; c0 < out.s.cols; c0 += tile) {
            const GridWindow part = GridWindow{c0, r0, c0 + tile, r0 + tile}.clamped(out.s.cols, out.s.rows);
            pos.resize(std::size_t(part.cols()) * std::size_t(part.rows())), valid.resize(pos.size());
            read_sampled(nodes, out.s, part, pos.data(), valid.data());
            for (int r = part.r0; r < part.r1; ++r)
                for (int c = part.c0; c < part.c1; ++c) {
                    const std::size_t from = std::size_t(r - r0) * std::size_t(part.cols()) + std::size_t(c - c0);
                    out.pos[std::size_t(r) * std::size_t(out.s.cols) + std::size_t(c)] = pos[from];
                    out.valid[std::size_t(r) * std::size_t(out.s.cols) + std::size_t(c)] = valid[from];
                }
        }
    return out;
}

// The sampled nodes of a cache's nodes are what they are on the Terrain's own, bit for bit (x, y
// derived for the sampled nodes alone, where the cache derives them), read whole or in tiles of
// 5 x 5: the whole grid, windows reaching the last column and row or not, steps within a block
// (256 nodes) and past it; none of the blocks is read into place (their memory not kept). Then,
// with rows of the grid read into place (a frame's mesh), the same again, those rows taken from
// memory.
void expect_sampled_as_in_memory(const StoredTerrain& map, const Terrain& t) {
    const GridNodes mem = grid_nodes(t);
    const CheckedBlocks& blocks = *map.nodes.blocks;
    const GridWindow windows[] = {{0, 0, t.cols, t.rows}, {3, 5, t.cols - 1, t.rows}, {t.cols / 3, 1, t.cols, t.rows / 2}};
    for (const bool some_in_place : {false, true}) {
        SCOPED_TRACE(some_in_place ? "rows read into place" : "nothing read into place");
        if (some_in_place) map.nodes.need(GridWindow{0, t.rows / 4, t.cols, t.rows / 2});
        for (const GridWindow& w : windows)
            for (const int step : {1, 2, 3, 4, 7, 64, 300})
                for (const int tile : {0, 5}) {
                    const Sampled want = sample(mem, w, step), got = sample(map.nodes, w, step, tile);
                    ASSERT_EQ(got.s.cols, want.s.cols);
                    ASSERT_EQ(got.s.rows, want.s.rows);
                    ASSERT_EQ(got.pos.size(), want.pos.size());
                    ASSERT_EQ(std::memcmp(got.pos.data(), want.pos.data(), want.pos.size() * sizeof(glm::vec3)), 0)
                        << w.c0 << " " << w.r0 << " step " << step << " tile " << tile;
                    ASSERT_EQ(got.valid, want.valid) << w.c0 << " " << w.r0 << " step " << step << " tile " << tile;
                }
        EXPECT_GT(blocks.bytes_read(), 0u);
        for (int r = 0; r < t.rows; ++r) {
            // (the blocks at the ends of the rows read hold nodes of the rows beside them)
            if (some_in_place && r >= t.rows / 4 - 1 && r <= t.rows / 2) continue;
            for (const int c : {0, t.cols / 2, t.cols - 1})
                for (const int k : {GridNodes::pos_array, GridNodes::valid_array})
                    ASSERT_FALSE(blocks.has_read(k, map.nodes.index(c, r))) << c << " " << r;
        }
    }
}

// Writes t's cache to `path` and reads it back whole: every node's position bit for bit and its
// flag, and an oblique frame's mesh, as in memory; the georeference of a geographic DEM too.
// Before that, every step-th node of windows, sampled as in memory (expect_sampled_as_in_memory).
void expect_round_trip(const Terrain& t, const std::string& path) {
    const StoredTerrain mem = store_terrain(t);
    write_terrain_cache(path, mem, key());
    const std::optional<StoredTerrain> map = read_terrain_cache(path, key());
    ASSERT_TRUE(map);
    EXPECT_EQ(map->meta.source_geographic, t.source_geographic);
    EXPECT_EQ(map->meta.angular_unit, t.angular_unit);
    EXPECT_EQ(map->meta.prime_meridian, t.prime_meridian);
    expect_sampled_as_in_memory(*map, t);
    read_whole(*map);
    for (std::size_t i = 0; i < t.size(); ++i) {
        ASSERT_EQ(std::memcmp(&map->nodes.pos[i], &t.pos[i], sizeof(glm::vec3)), 0) << i;  // bit for bit
        ASSERT_EQ(map->nodes.valid[i], t.valid[i]) << i;
    }
    const Camera cam = oblique(mem, 2.0);
    expect_same_mesh(select_lod_mesh(mem.lod, mem.drawn(2.0), 2.0, cam, LodOptions{}),
                     select_lod_mesh(map->lod, map->drawn(2.0), 2.0, cam, LodOptions{}));
}

// `t` round-trips bit for bit (expect_round_trip) both as it is, its x, y derived by the cache, and
// with one node's coordinate a float step off, its x, y stored; returns the two files' sizes
// (derived, stored).
std::pair<double, double> derived_and_stored_sizes(const test::TempDir& dir, const Terrain& t, int c, int r, bool y) {
    Terrain off = t;
    float& v = y ? off.pos[off.index(c, r)].y : off.pos[off.index(c, r)].x;
    v = std::nextafter(v, 1e9f);
    {
        SCOPED_TRACE("derived");
        expect_round_trip(t, dir.file("derived.lod"));
    }
    {
        SCOPED_TRACE("one node off");
        expect_round_trip(off, dir.file("off.lod"));
    }
    return {double(std::filesystem::file_size(dir.file("derived.lod"))), double(std::filesystem::file_size(dir.file("off.lod")))};
}

// On an affine grid (a projected DEM: every node's x, y is affine_node_xy of the geotransform, as
// the DEM reader computes them) the cache stores z alone and derives x, y as it reads: the nodes
// and the frames come back bit for bit, in a smaller file than the same terrain with one node's x
// a float step off the grid, whose x, y are all stored (and come back as well, that node too).
TEST(TerrainCache, XYOfAnAffineGridAreDerivedNotStored) {
    test::TempDir dir;
    const Terrain grid = on_affine_grid(hills());
    const auto [derived, stored] = derived_and_stored_sizes(dir, grid, 150, 100, false);
    // the derived file holds the node lattice besides (terrain_lod.hpp: its nodes' x, y are derived)
    const std::optional<StoredTerrain> d = read_terrain_cache(dir.file("derived.lod"), key());
    ASSERT_TRUE(d);
    EXPECT_EQ(d->lod.lattice_step, lod_lattice_step);
    const double lattice = derived - double(d->nodes.blocks->file_offset(TerrainLod::lattice_array));
    std::printf("x, y derived: %.0f bytes (%.0f of them the lattice); stored: %.0f\n", derived, lattice, stored);
    EXPECT_GT(lattice, 0.0);
    EXPECT_LT(derived - lattice + 0.4 * double(grid.size()), stored);  // x, y coded take 0.65 bytes a node here
}

// On a geographic DEM read whole (examples/jacksboro.tif, WGS 84) the DEM reader projects each
// node's longitude, latitude to UTM (input/geographic_nodes.hpp): the cache stores z alone and
// recomputes x, y as it reads, bit for bit as the reader made them, in a smaller file than the
// same terrain with one node's y a float step off, whose x, y are all stored (and come back too).
TEST(TerrainCache, XYOfAGeographicDemAreDerivedBitForBit) {
    test::TempDir dir;
    const Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    ASSERT_TRUE(dem.source_geographic);
    GeographicNodes g;
    ASSERT_TRUE(terrain_geographic(dem, g));
    const auto [derived, stored] = derived_and_stored_sizes(dir, dem, 200, 170, true);
    std::printf("jacksboro: x, y derived: %.0f bytes; stored: %.0f\n", derived, stored);
    EXPECT_LT(derived + 0.4 * double(dem.size()), stored);
}

// A geographic DEM's cache keeps the UTM lattice its x, y are interpolated from (the last array,
// 16 bytes a lattice node, as UtmRowProjector::lattice gives them): read and checked when the
// cache is opened (a damaged byte there fails the open), the nodes' x, y from it the DEM's, bit
// for bit. A projected DEM's has none.
TEST(TerrainCache, GeographicDemKeepsItsUtmLattice) {
    test::TempDir dir;
    const Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    const std::string path = dir.file("j.lod");
    write_terrain_cache(path, store_terrain(Terrain(dem)), key());
    std::vector<char> bytes = file_bytes(path);
    std::uint64_t at[8];
    std::memcpy(at, bytes.data() + 232, sizeof at);
    ASSERT_EQ(at[7], bytes.size());
    GeographicNodes g;
    ASSERT_TRUE(terrain_geographic(dem, g));
    EXPECT_EQ(at[7] - at[6], geographic_projector(g).lattice_size() * sizeof(glm::dvec2));
    {
        const std::optional<StoredTerrain> t = read_terrain_cache(path, key());
        ASSERT_TRUE(t);
        read_whole(*t);
        for (std::size_t i = 0; i < dem.size(); i += 7) {
            const glm::vec3 p = t->nodes.at(i);
            ASSERT_TRUE(std::memcmp(&p, &dem.pos[i], sizeof p) == 0) << i;
        }
    }
    bytes[std::size_t(at[6] + (at[7] - at[6]) / 2)] ^= 0x10;
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), std::streamsize(bytes.size()));
    }
    std::string why;
    EXPECT_FALSE(read_terrain_cache(path, key(), &why));
    EXPECT_EQ(why, "damaged terrain cache (UTM lattice)");
    // the volcano: x, y affine, no lattice
    write_terrain_cache(path, store_terrain(read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc")), key());
    bytes = file_bytes(path);
    std::memcpy(at, bytes.data() + 232, sizeof at);
    EXPECT_EQ(at[6], at[7]);
    EXPECT_EQ(at[7], bytes.size());
}

// build_terrain_cache (heights alone, the pyramid in strips, blocks coded as they are final)
// writes the file the whole Terrain writes, byte for byte: on a projected DEM (the volcano: x, y
// affine; a padded side of 129, under a block, so blocks cross the rows the upper levels hold
// back) and on a geographic one (jacksboro: x, y projected to UTM; side 513, two strips). The
// file it writes opens and reads whole. Whatever the bands of its first pass over the DEM
// (DemRows), and on a south-up DEM with nodata nodes.
TEST(TerrainCache, StreamedBuildWritesTheFileOfTheWholeTerrain) {
    test::TempDir dir;
    std::vector<float> v(37 * 23);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float(std::sin(double(i) * 0.1) * 40.0 + double(i % 37));
    v[5] = v[300] = v[301] = v[338] = -9999.0f;
    const double nodata = -9999;
    const std::string south = test::write_tif(dir.file("s.tif"), 37, 23, v, {500, 10, 0, 100, 0, 10}, 2193, &nodata);
    for (const std::string& dem : {std::string(PENINK_SOURCE_DIR "/examples/volcano.asc"),
                                   std::string(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), south})
    for (int band_rows : {0, 1, 5}) {
        const std::string whole = dir.file("whole.lod"), streamed = dir.file("streamed.lod");
        write_terrain_cache(whole, store_terrain(read_dem(dem)), key());
        int stages = 0;
        ASSERT_TRUE(build_terrain_cache(dem, streamed, key(), [&](int s) { EXPECT_EQ(s, stages++); }, band_rows));
        EXPECT_EQ(stages, 2);
        const std::vector<char> a = file_bytes(whole), b = file_bytes(streamed);
        EXPECT_GT(a.size(), 1000u) << dem;
        EXPECT_TRUE(a == b) << dem << ": " << a.size() << " vs " << b.size() << " bytes";
        const std::optional<StoredTerrain> t = read_terrain_cache(streamed, key());
        ASSERT_TRUE(t) << dem;
        EXPECT_NO_THROW(read_whole(*t));
    }
}

TEST(TerrainCache, StreamedBuildReportsTheDemsErrorsAndUnwritablePlaces) {
    test::TempDir dir;
    EXPECT_THROW(build_terrain_cache(dir.file("none.tif"), dir.file("x.lod"), key()), Error);
    const std::string path = dir.file("missing/v.lod");
    try {
        build_terrain_cache(PENINK_SOURCE_DIR "/examples/volcano.asc", path, key());
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: surface: " + path + ": cannot write terrain cache: No such file or directory");
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}
