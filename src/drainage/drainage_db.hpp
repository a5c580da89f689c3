// The drainage vertex database (DV file, Mower, "Concurrent Drainage Network Rendering" sec. 3): branches of drainage vertices (local
// x, y, z in metres of the Terrain's world frame — easting = origin.x + x, northing = origin.y + y
// in the projected CRS; z unexaggerated — normalised flow, Strahler order, basin) with
// downstream/upstream links, the divide (ridge) polylines, and the creases and ridges drawn from
// them, smoothed and draped on the PN surface (line_set.hpp). Binary, little-endian, versioned,
// in two checksummed parts (the network; the lines, which a render reads alone); the layout is
// documented in drainage_db.cpp and docs of write_drainage_db.
#pragma once
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/big_allocator.hpp"
#include "core/error.hpp"
#include "core/hash64.hpp"
#include "core/checked_blocks.hpp"
#include "drainage/line_set.hpp"
#include "input/terrain.hpp"

namespace penink {

// 16 bytes; a vertex's basin and Strahler order are its branch's (DvBranch). Trivial (no member
// initialisers): DvVertex{} is all zeros, a DvVertices element made by resize is left as the
// memory was (see UninitAllocator).
struct DvVertex {
    float x, y, z;  // local metres (z = original, unfilled elevation)
    float flow;     // accumulation / basin total, in (0, 1]; 0 on divides
    bool operator==(const DvVertex&) const = default;
};

using DvVertices = std::vector<DvVertex, UninitAllocator<DvVertex>>;

// A run of drainage points from a source (ridge point) or junction down to the next junction or
// outlet; a branch ending at a junction repeats the junction as its last vertex. Trivial like
// DvVertex (DvBranch{} is all zeros: set downstream to -1 for an outlet branch).
struct DvBranch {
    std::uint32_t first, count;          // vertices [first, first + count)
    std::int32_t downstream;             // branch starting at the end junction, -1 at outlets
    std::uint32_t up_first, up_count;    // upstream branch ids in DrainageDb::upstream
    std::uint32_t basin;
    std::uint32_t head_acc;              // accumulation at the head (points): vertex k has head_acc + k
    std::uint8_t order;                  // Strahler order of the branch
    bool operator==(const DvBranch&) const = default;
};
using DvBranches = std::vector<DvBranch, UninitAllocator<DvBranch>>;

struct DvPolyline {
    std::uint32_t first = 0, count = 0;  // vertices in DrainageDb::divide_vertices
    bool operator==(const DvPolyline&) const = default;
};

// What the database was built from: the DEM file (size, mtime, hash of its first and last MiB)
// and the build options. A different fingerprint means the database is stale.
struct DrainageFingerprint {
    std::uint64_t file_size = 0;
    std::int64_t mtime_ns = 0;
    std::uint64_t content_hash = 0;
    std::uint32_t resample = 1;
    std::uint32_t options = 0;  // 0 (reserved: the vertical exaggeration does not change the database)
    std::uint32_t routing = 0;  // flow routing method (DrainageRouting in drainage_build.hpp)
    bool operator==(const DrainageFingerprint&) const = default;
};

struct BuiltNetwork;  // crease_source.hpp
// A build's arrays handed on with its database: not part of the database's value (two databases
// compare equal whether or not either holds them).
struct BuiltNetworkHandle {
    std::shared_ptr<BuiltNetwork> arrays;
    explicit operator bool() const { return arrays != nullptr; }
    BuiltNetwork* operator->() const { return arrays.get(); }
    bool operator==(const BuiltNetworkHandle&) const { return true; }
};

struct DrainageDb {
    DrainageFingerprint fingerprint;
    std::int32_t cols = 0, rows = 0, factor = 1;  // drainage grid
    glm::dvec2 origin{0.0};                        // projected easting/northing of local (0, 0)
    std::string crs_wkt;
    DvVertices vertices;
    DvBranches branches;
    std::vector<std::uint32_t> upstream;  // upstream branch ids, referenced by DvBranch
    DvVertices divide_vertices;
    std::vector<DvPolyline> divides;
    // What frames draw: the stems (creases) and divides (ridges) smoothed and draped on the PN
    // surface of the DEM (draped_lines.hpp), unexaggerated.
    DrapedLineSet creases, ridges;
    // What building the creases reads, coded (crease_source.hpp), where they are built where a
    // frame needs them (a cache `penink drainage` writes): `creases` is then empty. Empty where
    // `creases` holds them (a build in memory) or on a DEM without relief.
    std::vector<std::uint8_t> crease_source;
    // Where a render left the crease source in the file (read_drainage_line_index): crease_source
    // is then empty and its crease_source_size bytes are array 0 of these pages, each read and
    // checked the first time it is needed by its checksum in crease_source_sums (as the file stores
    // them: crease_source_page_sums).
    std::shared_ptr<const CheckedBlocks> crease_source_pages;
    std::uint64_t crease_source_size = 0;
    std::vector<std::uint64_t> crease_source_sums;
    // Where the DEM whose heights the crease source refers to (crease_source.hpp) is read now, when
    // it moved with its database (load_or_build_drainage: the same fingerprint, so the same bytes,
    // at another path; its heights read there are still checked by the source's block hashes);
    // empty: the path the source stores.
    std::string crease_source_dem;
    // After a build in this process (load_or_build_drainage): the grid, directions and network the
    // crease source codes, handed to the creases' tiles so that they are not made again
    // (StoredCreases::take); none for a database read from a file.
    BuiltNetworkHandle built_network;
    bool has_crease_source() const { return !crease_source.empty() || crease_source_pages; }
    bool operator==(const DrainageDb&) const = default;
};

// 3: layout of 2; directions with downstream tie-breaking and depressions drained down their
// original slopes (d8_ties.hpp, depression_drainage.hpp): files of 2 hold other networks, rebuilt.
// 4: the fingerprint gains the routing method (u32 after options).
// 5: branches carry their head's accumulation (DvBranch::head_acc) and are stored as varints;
// vertex flow is not stored but follows from it (12-byte vertices).
// 6: positions either explicit (x, y, z) or, on an affine grid at factor 1, as cells: each
// branch's head cell and a step per vertex (5-byte vertices).
// 7: each branch's vertices follow its record; the total length is written last into the header
// and hashed last (so a writer can stream branches it has not counted).
// 8: built from unexaggerated heights (the fingerprint's options are 0, not the vertical
// exaggeration); a second part, with its own checksum and its offset in the header, holds the
// creases and ridges smoothed, draped and indexed (line_set.hpp), which a render reads alone.
// 9: a line's length is its 3-D length (unexaggerated), which bounds its drawn length at any
// exaggeration, so a frame culls lines by their records alone; the lines part ends with a
// checksum of everything in it but the vertex arrays, which a render checks without reading them.
// 10: the creases follow the surface's fall line (fall_line_stems.hpp) and the ridges are
// smoothed by a Gaussian, both joined smoothly at junctions (the lines part's content, not its layout).
// 11: each line set's vertex array is followed by a checksum per block of 1024 vertices, which a
// render reading vertices from the file checks block by block.
// 12: the creases traced on the DEM nodes' own fall line in a corridor that widens on slopes, the
// ridges moved onto the surface's crest (ridge_crests.hpp) (content, not layout).
// 13: a crease whose fall line does not lead back to its junction ends where its trace ends, and
// a trace leaving the grid stops there (content, not layout).
// 14: the lines part stores, after the ridges, what building the creases reads (crease_source.hpp:
// the drainage grid, flow directions and crease tiles' index, coded) and no creases: a render
// builds those a frame needs, per tile, on first use.
// 15: a file storing the crease source stores no network but its counts (positions mode 2): the
// branches and divides follow from the grid and directions the crease source holds, made again
// on a whole read.
// 16: the crease tiles' index holds each stem's bound (stem_reach.hpp: StemBound, its reach's box
// and a bound of its crease's length), so a render builds only the stems its frame can draw.
// 17: a stem's bound keeps its cells' plan length and vertical travel apart (the crease's length
// at exaggeration e bounded by plan + e rise, not max(1, e) times the 3-D length).
// 18: the crease tiles' index stored by unit (a tile's stems of one length level: a table of their
// summaries, then each unit's stem ids and bounds coded alone), and the crease source followed by a
// checksum of each of its 64 KiB pages, outside the index checksum: a render leaves it in the file
// and reads the pages it needs.
// 19: the crease source stores the network its stems' walks read (each basin's total, the
// junctions' mains, and the cells' accumulation, basin and order by square blocks): a render
// decodes the blocks its walks reach instead of computing the network from the directions.
// 20: a DEM reference holds a hash of each block of heights (DemArraysHash::z), which a render
// reads by blocks from its terrain cache.
inline constexpr std::uint32_t drainage_db_version = 20;

// Fingerprint of the DEM file at `dem_path` with the given resample factor: its size, mtime and
// a hash of its whole content (streamed) and of every side file GDAL may read with it (world
// file, .prj, .aux.xml: input/dem_side_files.hpp), so a DEM changed in place with the same size
// and mtime, or a replaced .prj, does not match. Throws Error("input", dem_path, ...) for a path
// that is not a local regular file (core/input_files.hpp) and penink::Error("drainage",
// dem_path, "cannot read DEM file") when it cannot be read.
DrainageFingerprint dem_fingerprint(const std::string& dem_path, int resample);

// One branch as the DV file stores it (DvBranch without the derived first / upstream fields).
struct DvBranchRecord {
    std::uint32_t count;      // vertices, the repeated end junction included
    std::int32_t downstream;  // -1 at an outlet
    std::uint8_t order;
    std::uint32_t basin, head_acc;
};

// Encoded bytes of a part of a file; growing it leaves the new bytes unwritten (UninitAllocator),
// so encoders size it for the most they may write and trim it after.
using DvBytes = std::vector<std::uint8_t, UninitAllocator<std::uint8_t>>;

// The branches an encoding is written from: a DrainageDb's (what encode_drainage_db /
// write_drainage_db use) or the drainage network's own, streamed without holding the vertices
// (NetworkBranches, branches.hpp). encode() is called for consecutive ranges of branch ids from
// several threads at once.
class DvBranchSource {
public:
    virtual ~DvBranchSource() = default;
    virtual std::size_t branch_count() const = 0;
    virtual std::size_t vertex_count() const = 0;  // repeated end junctions included
    virtual std::size_t link_count() const = 0;    // branches with a downstream branch
    // Grid positions: non-null when every vertex is a node of the drainage grid (cols wide) lying
    // on this affine grid (x, y = affine_node_xy at the node); the file then stores cells, not x, y.
    virtual const AffineNodes* grid_nodes() const { return nullptr; }
    // Appends branches [b0, b1) to `out` as the file stores them (dv_format.hpp: append_branch):
    // each its record, then its vertices but a repeated end junction.
    virtual void encode(std::size_t b0, std::size_t b1, DvBytes& out) const = 0;
};

// Every branch's up_first / up_count and the upstream id list they index, from the downstream
// links (in range, -1 at outlets), upstream branches in branch order.
void link_upstream(DvBranches& branches, std::vector<std::uint32_t>& upstream);

// Serialised bytes (header, counts, data, trailing checksum). The compact layout needs `db` in
// the shape drainage_db_from_grid gives it; a database whose layout breaks it (vertex ranges,
// links, basin ids: cheap checks) throws penink::Error("drainage", "", "drainage database is not
// in the shape the builder gives it", internal); what is derived on reading (repeated junction
// vertices, upstream lists, flows) is the builder's invariant, not checked here (tests check it).
std::vector<std::uint8_t> encode_drainage_db(const DrainageDb& db);

// Streams the encoding (4 MiB buffer) to a temp file in the same directory, then renames it. Throws
// penink::Error("drainage", path, "cannot write drainage database", internal) on failure.
void write_drainage_db(const std::string& path, const DrainageDb& db);

// The same file for the header and divides of `meta` (its vertices and branches unused) with the
// branches and vertices of `branches`, which must have the builder's shape (not checked).
void write_drainage_db(const std::string& path, const DrainageDb& meta, const DvBranchSource& branches);

// What a read decodes: the whole database, or only the part a render draws from (fingerprint,
// cols, rows, factor, origin, creases and ridges; the rest empty), read and checked alone.
enum class DvParts { all, lines };

// The fingerprint in the header of the database at `path` (its first bytes alone: the prefix
// checked as a read checks it, nothing else); nullopt when there is none, it is not a database of
// this version or it ends before its fingerprint.
std::optional<DrainageFingerprint> peek_drainage_fingerprint(const std::string& path);

// Reads and checks a database (the parts it reads): errors penink::Error("drainage", path, what)
// with what = "cannot open drainage database", "not a drainage database (bad magic)",
// "unsupported drainage database version N (expected M)", "truncated drainage database",
// "drainage database checksum mismatch (file corrupt)",
// "drainage database is stale (DEM changed)" (when expected is given and differs; on a whole
// read also when the crease source's heights are its DEM's and the DEM at its path changed or
// is gone: crease_source.hpp).
DrainageDb read_drainage_db(const std::string& path, const DrainageFingerprint* expected = nullptr,
                            DvParts parts = DvParts::all);
DrainageDb decode_drainage_db(const std::vector<std::uint8_t>& bytes, const std::string& path);

// Where the vertices of the lines part stay when a render reads only its line records and index
// (read_drainage_line_index): the open file (a cache replaced by a rename later leaves it as it
// was) and the offsets of the creases' (set 0) and ridges' (set 1) vertex arrays, whose bytes the
// read has hashed and checked.
struct DvLineVertices {
    std::shared_ptr<std::FILE> file;
    std::string path;
    std::uint64_t at[2] = {0, 0};     // file offsets of the vertex arrays
    std::uint64_t count[2] = {0, 0};  // vertices in each
    std::vector<std::uint64_t> block_sums[2];  // checksum of each block of 1024 vertices (dv_format.hpp)
    // Per block of either set (set 0's first): checked already. Shared by copies.
    std::shared_ptr<std::vector<std::atomic<bool>>> checked;
    // Vertices [first, first + n) of set 0 or 1 into out (pread: any thread). The first read from
    // a block reads the whole block and checks its checksum. Throws DvCorrupt for a block that
    // does not match or a file that has shrunk since.
    void read(int set, std::uint64_t first, std::uint64_t n, DrapedVertex* out) const;
};

// A drainage database found damaged while a render reads it (DvLineVertices::read): the caller
// reads the database again whole (every checksum checked) or rebuilds it.
class DvCorrupt : public Error {
public:
    using Error::Error;
};

// The lines part's line records and index, as DvParts::lines reads them (the same errors), its
// vertex arrays neither read nor kept: the creases and ridges hold their lines and index, no
// vertices (line_set_ok holds for the stored counts); `vertices` says where they are. What is
// read is checked by the index checksum; the vertices are not read to check them (a render reads
// only those it draws; every count and offset is checked, so a damaged vertex can change a line's
// shape, never what is read). Time and memory in proportion to the lines, not the vertices.
DrainageDb read_drainage_line_index(const std::string& path, const DrainageFingerprint* expected,
                                    DvLineVertices& vertices);

// `db` as a lines-only read gives it (DvParts::lines): the network, divides and CRS dropped.
DrainageDb drainage_lines_only(DrainageDb db);

}  // namespace penink
