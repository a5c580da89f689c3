// The terrain cache: a DEM's nodes (plan positions, unexaggerated heights, data flags) and its
// level-of-detail pyramid (terrain_lod.hpp), written once per DEM beside the drainage database
// and read back by later renders, which then skip reading the DEM and building the pyramid.
// Keyed by the DEM file (size, modification time, hash of its whole content and side files, as
// the drainage database is keyed: dem_fingerprint) and by the UTM zone a geographic DEM is
// projected to; never by view, style, light or vertical exaggeration.
//
// Frames and units: the Terrain's local metres (x east, y north, z elevation unexaggerated),
// row 0 north (conventions.md); GridNodes::z_scale draws them at any exaggeration.
//
// File layout, little-endian, version 9 (one header, then seven coded arrays):
//   "PENINKTC", u32 version, u32 header length (bytes, up to and including its checksum)
//   key: u64 DEM file size, i64 mtime (ns), u64 content hash, i32 forced UTM zone, u32 north,
//        u64 the DEM file's identity when the hash was made (TerrainCacheKey::identity; the one
//        field not under the header's checksum: record_terrain_identity writes it in place)
//   grid: i32 cols, rows, levels, u32 source_geographic; f64 origin x, y; f64 geotransform[6];
//         f64 xy_unit, elevation_min, elevation_max; i32 utm_zone, u32 north;
//         f64 angular_unit, prime_meridian
//   pyramid: f32 lipschitz, z_min, z_max, 0; f64 plan bounds lo.x, lo.y, hi.x, hi.y
//   u64 offsets of pos, valid, error, lattice, coarse, edges, utm; u64 file length; u64 CRS length,
//     CRS WKT bytes (padded to 8)
//   u32 block shift s (blocks of 2^s elements: 256), u32 flags (1 or 2: x, y not stored, see
//     below); u32 lattice step (lod_lattice_step, or 0: no lattice), u32 coarse step
//     (grid_coarse_step, or 0: none), u32 edges (1: the edge columns kept, 0: not), u32 utm (1:
//     the UTM lattice kept, flag 2 only, 0: not); u32 coded size of each block of pos, then of
//     valid, error, lattice, coarse, edges and utm (each array
//     cut into blocks of elements from its start, the last one short; padded to 8); u64 hash64 of
//     each block's coded bytes, in the same order
//   u64 checksum: hash64 of every header byte before it but the identity's (header_checksum)
//   then each array's blocks, coded (core/block_codec.hpp), back to back: pos (f32 x, y, z per
//   node, cols * rows: encode_floats, x, y differenced twice, z once; with flag 1 or 2, z alone,
//   differenced once, the x, y recomputed as the DEM reader computes them: flag 1,
//   affine_node_xy on the grid's geotransform and xy_unit (a projected DEM); flag 2, the UTM
//   projection of the node's longitude, latitude (input/geographic_nodes.hpp: a geographic DEM
//   read whole); written so only when the formula gives every node's x, y bit for bit),
//   valid (u8 per node: encode_bytes), error (f32 per node, cols * rows: encode_floats as they
//   are; the padded square's other nodes are all +inf, not stored: TerrainLod::error), and
//   with flag 1 or 2 the node lattice (terrain_lod.hpp's LatticeNode, nine f32 per node of every
//   8th row and column, lattice_size(cols) x lattice_size(rows): encode_floats, the heights
//   differenced once, flags and error as they are; what a coarse mesh's selection reads, 9 MiB
//   more on jacksboro refined 29 times) and the coarse nodes (input/grid_nodes.hpp's CoarseNode,
//   every 4th node of every 4th row: f32 height differenced once, f32 flag; what a sampled grid
//   of a step of 4 or more reads, the hachures' on a DEM finer than the pixels: 4 MiB more there,
//   108 MiB in all) and the edge columns (CoarseNode of column 0's nodes, then of column
//   cols - 1's: what the automatic camera frames besides the first and last rows); with flag 2
//   the UTM lattice (utm_projection.hpp: the f64 easting, northing of the exactly projected
//   nodes the others' x, y are interpolated from, UtmRowProjector::lattice, as in memory; read
//   whole and checked when the file is opened, so that a frame projects none of them: on
//   jacksboro refined 29 times 456 k nodes, 7.3 MB, 115 MiB in all, about 0.25 s of CPU and 0.13 s
//   of a whole view's 2.8 s spared).
// The coding is lossless: a frame drawn from the file is the frame drawn from memory, bit for bit.
// Its size follows the DEM's smoothness: 1.35 bytes a node (0.34 of the DEM's float32 heights) on
// jacksboro refined 10 times (13.9 M nodes, geographic: x, y derived; 1.15 without the lattice and
// the coarse nodes), 0.98 refined 29 times (0.85), 1.75 refined 5 times (1.43); before the
// lattice about 2 on examples/volcano.asc (projected), 2.8 on
// examples/jacksboro.tif (1" heights in whole metres, rough at the cell scale); stored as floats
// it took 17 and more. (`penink render DEM --cache-dir D`, then the size of D/*.lod;
// bench/terrain_cache_bench.cpp.)
// The header is checksummed and every length and offset is checked against the grid and the
// file's size when the file is opened: a flipped header byte, a cut or a foreign file is refused
// with its reason, and the caller rebuilds the cache. The arrays are read on demand
// (core/checked_blocks.hpp: pread, never mapped, so a file cut short meanwhile cannot fault the
// process), each block checked against its checksum and then decoded into place: a frame reads,
// checks and decodes only the blocks its level-of-detail selection and its view
// window touch (GridNodes::need; the selection through CheckedBlocks::Cached, keeping none), so
// its time and memory follow the image,
// not the DEM. A damaged block is found when it is first needed and throws DamagedBlockError;
// draw_scene (scene/frame_source.hpp) then removes the cache and draws again from a rebuilt one.
// Written to a temporary file and renamed into place. Built from a DEM file by
// build_terrain_cache in bounded memory: a window of the DEM's rows, the pyramid's strips
// (lod_errors), the coded blocks and the node lattice, held whole until written (36 bytes every
// 64 nodes: 0.56 bytes a node): 505 MB at peak for jacksboro refined 29 times (116.6 M nodes,
// 108 MiB written; 402 MB before the lattice and the coarse nodes) where the whole Terrain and
// pyramid took 5.19 GB, 2.31 GB for 1.0 G nodes before the lattice, about 3.2 GB with it by the
// estimate (scene/cache_build_estimate.cpp; bench/terrain_cache_build_bench.cpp; docs/timings.md,
// "Scale").
#pragma once
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <glm/vec2.hpp>

#include "input/grid_nodes.hpp"
#include "input/terrain.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

inline constexpr std::uint32_t terrain_cache_version = 9;

// identity: the DEM file's identity when the key was made (input/dem_file_identity.hpp), stored
// with it but not compared (a copy of the DEM has another identity and the same key): a cache
// whose recorded identity is the DEM's now gives its key without the DEM being read
// (recorded_terrain_key). 0: none recorded.
struct TerrainCacheKey {
    std::uint64_t file_size = 0;
    std::int64_t mtime_ns = 0;
    std::uint64_t content_hash = 0;
    std::int32_t utm_zone = 0;  // the zone forced on a geographic DEM (DemOptions::utm_zone), 0 none
    bool north = true;
    std::uint64_t identity = 0;
    bool operator==(const TerrainCacheKey& o) const {
        return file_size == o.file_size && mtime_ns == o.mtime_ns && content_hash == o.content_hash &&
               utm_zone == o.utm_zone && north == o.north;
    }
};

// A DEM's nodes and pyramid, held in memory (built, or read from a cache file).
struct StoredTerrain {
    Terrain meta;     // grid size and georeference; pos, valid, z, xy empty; vertical_exaggeration 1
    GridNodes nodes;  // z unexaggerated (z_scale 1); points into `storage`
    TerrainLod lod;
    glm::dvec2 plan_lo{0.0}, plan_hi{0.0};  // plan bounds of the valid nodes, metres
    std::shared_ptr<const void> storage;    // owns what `nodes` points to
    // The whole Terrain when it was read from the DEM in this process (nodes point into it); null
    // when read from a cache file.
    const Terrain* in_memory = nullptr;
    // The DEM file's identity it was read or built for (open_stored_terrain; zero when made from
    // a Terrain alone): what other caches of the same run key themselves by too.
    TerrainCacheKey key;

    // The nodes as drawn at a vertical exaggeration, with water at a sea level (unexaggerated;
    // -inf: none, GridNodes::sea_level).
    GridNodes drawn(double exaggeration, double sea_level = -std::numeric_limits<double>::infinity()) const {
        GridNodes n = nodes;
        n.z_scale = exaggeration;
        n.sea_level = sea_level;
        return n;
    }
};

// From a Terrain read unexaggerated (vertical_exaggeration 1; its arrays are moved in): builds the
// pyramid. Throws std::invalid_argument on a Terrain with another exaggeration or mismatched arrays.
StoredTerrain store_terrain(Terrain flat);

// Writes the cache (a temporary file beside `path`, renamed into place). Throws penink::Error
// (stage "surface", file path) with the system's reason when it cannot be written.
void write_terrain_cache(const std::string& path, const StoredTerrain& terrain, const TerrainCacheKey& key);

// Builds the cache of the DEM at `dem_path` (read_dem, unexaggerated) into `path` holding a band
// of its rows at a time, never the whole DEM, its positions or the whole pyramid: the DEM is read
// by bands twice (input/dem_reader.hpp, DemRows: once for its errors and lowest elevation, then
// as the pyramid's strips need its rows, lod_errors), each row's x, y checked against the formula
// the cache recomputes them with and reduced to the plan bounds and the Lipschitz bound, the
// nodes' blocks coded and written as their rows come, the flags' coded and held until then, the
// pyramid's coded as each is final and written last; the file is write_terrain_cache's, byte for
// byte. Memory: the window of rows a strip reads (about 600 rows of 5 bytes a node), the strips
// (lod_errors_bytes) and the coded flags and pyramid, with an entry for each block of the pyramid.
// done(0) after the first pass over the DEM, done(1) after the pyramid and the nodes' coding (may
// be empty). band_rows: the first pass's band (0: DemRows' default). False, nothing written,
// when the x, y follow no formula bit for bit (a DEM reader's change): the caller then builds it
// from the whole Terrain (store_terrain, write_terrain_cache). Throws read_dem's errors, and
// penink::Error (stage "surface", file path) when the file cannot be written.
bool build_terrain_cache(const std::string& dem_path, const std::string& path, const TerrainCacheKey& key,
                         const std::function<void(int)>& done = {}, int band_rows = 0);

// Opens a cache file: reads and checks its header only (the arrays are read as they are needed).
// nullopt, with the reason in *why, when it is missing, not a regular file (a FIFO, a folder:
// never opened for blocking reads), of another version, built from another DEM (key), or its
// header is damaged (header checksum, lengths, offsets, block checksums' count).
std::optional<StoredTerrain> read_terrain_cache(const std::string& path, const TerrainCacheKey& key,
                                                std::string* why = nullptr);

// The key recorded in the cache file at `path`, identity included: its first 56 bytes alone
// (magic, version and header length checked, not the header's checksum, which read_terrain_cache
// checks with the rest of it: a key read from a damaged header only names the cache to try, and a
// cache that then does not open is built again under the DEM's hashed key); nullopt when there is
// no such file or its start is not a terrain cache's of this version.
std::optional<TerrainCacheKey> recorded_terrain_key(const std::string& path);
// Records `identity` in the cache file at `path` (a terrain cache of this version), in place:
// what a render that hashed the DEM and found the cache sound does where the recorded identity
// was another's (the DEM moved, copied, or its status changed with its bytes the same: a new
// link, chmod), so the next render takes the key without reading the DEM again. A field of its
// own written with one pwrite of its 8 bytes, outside the header's checksum: a reader sees the
// old identity or the new one, and either only saves or costs a hash. False where it cannot be
// written (a read-only file or folder, not such a cache); nothing else changes.
bool record_terrain_identity(const std::string& path, std::uint64_t identity);

// Reads and checks every block of a terrain opened from a cache file (a no-op for one in memory).
// Throws DamagedBlockError at the first damaged block.
void read_whole(const StoredTerrain& t);

}  // namespace penink
