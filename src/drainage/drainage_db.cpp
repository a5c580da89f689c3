// DV file layout (version 18, all little-endian; compact: what the builder's invariants give is
// not stored, see layout_ok). Two parts, each with its checksum: the network
// (header, branches, divides) and the lines (creases and ridges for drawing, line_set.hpp),
// which a render reads and checks alone (read_drainage_db, DvParts::lines). A file holding the
// creases' source (what `penink drainage` and a render's cache write) stores no branches or
// divides: they follow from the drainage grid and flow directions it holds (positions 2 below).
//   char[8]  magic "PNKDV\0\0\0"
//   u32      format version
//   u32      reserved (0)
//   u64      total file length in bytes (checksums included); written last
//   u64      offset of the lines part (a multiple of 8); written last
//   fingerprint: u64 DEM size, i64 DEM mtime (ns), u64 DEM hash, u32 resample, u32 options (0),
//            u32 routing
//   i32 cols, rows, factor; f64 origin easting, northing; u32 n + n bytes of CRS WKT
//   u8 positions: 0 explicit, 1 grid cells (then f64 gt[6], f64 unit, i32 col0, row0), 2 none:
//            the network is made again from the crease source (lines part) on a whole read
//            (decode_crease_source, network_of_directions, build_branches, build_divides: the
//            database built in memory, bit for bit); nothing follows the counts, which the network
//            made must match
//   u64 counts: vertices, branches, upstream links, divide vertices, divides
//   (positions 0 and 1) branches, each a record then its stored vertices:
//     record: varint count; varint link: 0 for an outlet branch, else zigzag(downstream - own
//             id); u8 order; varint basin; varint head_acc; with grid positions varint head cell
//             minus the branch before's (varint: LEB128, 7 bits a byte, low first; zigzag: 2d for
//             d >= 0, -2d - 1 below). first = running sum of counts; upstream lists follow from
//             the links
//     vertices: all but the end junction of a branch with a downstream branch (= that branch's
//             first vertex): f32 x, y, z (12 bytes each), or with grid positions f32 z for the
//             head and u8 step (ESRI code index of the move) + f32 z for each next one; the flow
//             of vertex k is (head_acc + k) / the basin's total, the total being the
//             accumulation at the last vertex of the basin's outlet branch (head_acc + count - 1)
//   (positions 0 and 1) divides: u32 count (first = running sum); divide vertices: f32 x, y, z
//            (flow 0)
//   zero bytes up to a multiple of 8
//   u64      network checksum: hash64 (FNV-1a, 64-bit words) of every byte before it with the two
//            length fields read as 0, then of the lines part's offset (dv_format.hpp: network_hash)
// lines part (at its offset):
//   fingerprint as above, u32 0; i32 cols, rows, factor, u32 0; f64 origin easting, northing
//   creases, then ridges, each:
//     u64 lines, u64 vertices
//     lines: f32 box lo.x, lo.y, hi.x, hi.y, f32 3-D length (unexaggerated), u32 count, u8 order, 3 zero bytes
//            (first = running sum of counts)
//     vertices: f32 x, y, z, nx, ny, nz, flow (28 bytes each: DrapedVertex)
//     vertex block checksums: u64 hash64 of each block of 1024 vertices (dv::vertex_block; the
//            last one short), ceil(vertices / 1024) of them: a render that leaves the vertices in
//            the file checks each block the first time it reads from it (DvLineVertices::read)
//     index: f32 origin x, y, f32 level-0 cell side, u32 levels; u32 cols, rows per level; u32
//            cell starts (cells of all levels + 1); u32 line ids (one per line)
//   u64 n + n bytes: what building the creases reads (crease_source.hpp), coded; n = 0 where the
//            creases are stored (a database built in memory) or the DEM has no relief
//   u64      per 64 KiB page of those n bytes (the last short): its hash64 (crease_source_page_sums:
//            a render leaves the source in the file and checks each page it reads against these)
//   u64      index checksum: hash64 of the part's bytes before it but the two vertex arrays and the
//            crease source's bytes, as one array (what a render reads: it leaves those in the file,
//            read_lines_part)
//   u64      lines checksum: hash64 of the part's bytes before it, then of its offset and of the
//            total length (dv_format.hpp: lines_hash)
// Versions 2-4 stored each vertex's flow (16 bytes) and fixed 13-byte branches without head_acc;
// 4 added the routing; 5 varint records; 6 grid positions; 7 vertices after each record; 8 the
// lines part and no vertical exaggeration in the fingerprint; 9 3-D line lengths and the index
// checksum; 11 the vertex block checksums; 14 the crease source in place of the creases; 15 no
// network beside a crease source (positions 2); 18 the creases' index by unit and the source's
// page checksums.
#include "drainage/drainage_db.hpp"

#include <bit>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "input/dem_side_files.hpp"
#include "drainage/dv_format.hpp"

namespace penink {

static_assert(std::endian::native == std::endian::little, "DV files are written little-endian");

namespace dv {

bool basin_totals(const DrainageDb& db, std::vector<double>& total) {
    std::size_t outlets = 0;
    for (const DvBranch& b : db.branches) outlets += b.downstream < 0;
    total.assign(outlets, 0.0);
    for (const DvBranch& b : db.branches) {
        if (b.basin < 1 || b.basin > outlets) return false;
        if (b.downstream >= 0) continue;
        if (total[b.basin - 1] != 0.0 || std::uint64_t(b.head_acc) + b.count < 2) return false;
        total[b.basin - 1] = double(std::uint64_t(b.head_acc) + b.count - 1);  // >= 1
    }
    return true;
}

// The shape drainage_db_from_grid gives `db` that the compact layout relies on and encode checks
// (sequential, cheap; encode refuses a database failing it): branches' and divides' vertices
// consecutive, downstream links in range, basins of the outlet branches numbered 1..outlets. What
// is not stored is the builder's invariant, which tests check (dv_file_test.cpp): a branch
// ending at a junction repeats the downstream branch's first vertex; upstream lists derived from
// `downstream` in branch order; divide vertices with flow 0; vertex flows as head_acc and the
// basin totals give them (branch_flow).
bool layout_ok(const DrainageDb& db) {
    std::size_t next = 0, id = 0;
    for (const DvBranch& b : db.branches) {
        if (b.first != next || b.count < 1u + (b.downstream >= 0) || b.downstream < -1 ||
            b.downstream >= std::int64_t(db.branches.size()) || b.downstream == std::int64_t(id++))
            return false;
        next += b.count;
    }
    if (next != db.vertices.size()) return false;
    next = 0;
    for (const DvPolyline& p : db.divides) {
        if (p.first != next) return false;
        next += p.count;
    }
    std::vector<double> total;
    return next == db.divide_vertices.size() && basin_totals(db, total);
}

}  // namespace dv

void link_upstream(DvBranches& branches, std::vector<std::uint32_t>& upstream) {
    std::vector<std::uint32_t> count(branches.size() + 1, 0);
    for (const DvBranch& b : branches)
        if (b.downstream >= 0) ++count[std::size_t(b.downstream) + 1];
    for (std::size_t b = 0; b < branches.size(); ++b) {
        count[b + 1] += count[b];
        branches[b].up_first = count[b];
        branches[b].up_count = count[b + 1] - count[b];
    }
    upstream.assign(count.back(), 0);
    for (std::size_t b = 0; b < branches.size(); ++b)
        if (branches[b].downstream >= 0) upstream[count[std::size_t(branches[b].downstream)]++] = std::uint32_t(b);
}

namespace {

// Chains the hash of the whole file at `path` (1 MiB chunks, so each but the last is a multiple
// of 8 bytes and hash64 chains); false when it cannot be read.
bool hash_file(const std::string& path, std::uint64_t& h) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::vector<char> chunk(std::size_t(1) << 20);
    while (in) {
        in.read(chunk.data(), std::streamsize(chunk.size()));
        if (in.gcount() > 0) h = hash64(chunk.data(), std::size_t(in.gcount()), h);
    }
    return in.eof();
}

}  // namespace

DrainageFingerprint dem_fingerprint(const std::string& dem_path, int resample) {
    namespace fs = std::filesystem;
    check_input_file("input", dem_path);  // no FIFO or device: the hash below reads it whole
    std::error_code ec;
    DrainageFingerprint f;
    f.file_size = fs::file_size(dem_path, ec);
    const auto mtime = fs::last_write_time(dem_path, ec);
    if (ec) throw Error("drainage", dem_path, "cannot read DEM file");
    f.mtime_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(mtime.time_since_epoch()).count();
    f.content_hash = hash64(nullptr, 0);
    if (!hash_file(dem_path, f.content_hash)) throw Error("drainage", dem_path, "cannot read DEM file");
    for (const std::string& side : dem_side_files(dem_path)) {  // the CRS and georeference GDAL reads too
        if (!fs::is_regular_file(side, ec)) continue;
        const std::string name = fs::path(side).filename().string();
        f.content_hash = hash64(name.data(), name.size(), f.content_hash ^ 0x9e3779b97f4a7c15ull);
        hash_file(side, f.content_hash);
    }
    f.resample = std::uint32_t(resample);
    return f;
}

}  // namespace penink

