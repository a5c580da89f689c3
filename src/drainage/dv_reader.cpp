// Reading DV files (layout in drainage_db.cpp): every length, count, link and basin checked
// before it is used, the checksum before anything is decoded.
#include "drainage/drainage_db.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include <unistd.h>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/branches.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/d8.hpp"
#include "drainage/dv_format.hpp"

namespace penink {

namespace {

using namespace dv;

// Bytes [0, size) of a file or of its lines part, read front to back.
struct Bytes {
    const std::uint8_t* p;
    std::size_t n;
    std::size_t size() const { return n; }
    const std::uint8_t* data() const { return p; }
    std::uint8_t operator[](std::size_t i) const { return p[i]; }
};

struct Reader {
    Bytes buf;
    std::size_t pos;
    std::string path;
    [[noreturn]] void corrupt() const {
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    }
    std::size_t left() const { return pos > buf.size() ? 0 : buf.size() - pos; }
    void need(std::size_t n) const {
        if (pos > buf.size() || n > buf.size() - pos) corrupt();
    }
    template <class T> T get() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, buf.data() + pos, sizeof(T));
        pos += sizeof(T);
        return v;
    }
    std::uint64_t varint() {
        std::uint64_t v = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            need(1);
            const std::uint8_t b = buf[pos++];
            v |= std::uint64_t(b & 0x7f) << shift;
            if (!(b & 0x80)) return v;
        }
        corrupt();
    }
    // n elements of T copied out (n checked against the bytes left first).
    template <class T, class V> void array(V& out, std::uint64_t n) {
        if (n > (buf.size() - std::min(pos, buf.size())) / sizeof(T)) corrupt();
        out.resize(std::size_t(n));
        if (n) std::memcpy(out.data(), buf.data() + pos, std::size_t(n) * sizeof(T));  // no null pointers
        pos += std::size_t(n) * sizeof(T);
    }
};

// How the file stores the network (dv_format.hpp): with explicit or grid positions, or not at all
// (from_source: made again from the crease source; `counts` are the stored ones to check it by).
struct Positions {
    bool grid = false;
    bool from_source = false;
    AffineNodes nodes;
    std::uint64_t counts[5] = {};
};

DrainageFingerprint get_fingerprint(Reader& r) {
    DrainageFingerprint f;
    f.file_size = r.get<std::uint64_t>(), f.mtime_ns = r.get<std::int64_t>();
    f.content_hash = r.get<std::uint64_t>(), f.resample = r.get<std::uint32_t>();
    f.options = r.get<std::uint32_t>(), f.routing = r.get<std::uint32_t>();
    return f;
}

void get_header(Reader& r, DrainageDb& db, Positions& pos) {
    r.pos = prefix_bytes;
    db.fingerprint = get_fingerprint(r);
    db.cols = r.get<std::int32_t>(), db.rows = r.get<std::int32_t>(), db.factor = r.get<std::int32_t>();
    db.origin.x = r.get<double>(), db.origin.y = r.get<double>();
    const std::uint32_t n = r.get<std::uint32_t>();
    r.need(n);
    db.crs_wkt.assign(reinterpret_cast<const char*>(r.buf.data() + r.pos), n);
    r.pos += n;
    const std::uint8_t mode = r.get<std::uint8_t>();
    if (mode != positions_explicit && mode != positions_grid && mode != positions_source) r.corrupt();
    pos.grid = mode == positions_grid, pos.from_source = mode == positions_source;
    if (!pos.grid) return;
    for (double& v : pos.nodes.gt) v = r.get<double>();
    pos.nodes.unit = r.get<double>(), pos.nodes.col0 = r.get<std::int32_t>(), pos.nodes.row0 = r.get<std::int32_t>();
    if (db.cols < 1 || db.rows < 1) r.corrupt();
}

// A branch's stored vertices on grid nodes: from its head cell, a step (ESRI code index) before
// each next vertex's z; x, y where the affine grid puts the cell.
void get_grid_vertices(Reader& r, const DrainageDb& db, const Positions& pos, std::uint32_t head, DvVertex* out,
                       std::uint32_t stored) {
    if (stored == 0) return;
    r.need(std::size_t(stored) * 5 - 1);
    int c = int(head % std::uint32_t(db.cols)), row = int(head / std::uint32_t(db.cols));
    for (std::uint32_t k = 0; k < stored; ++k) {
        if (k > 0) {
            const std::uint8_t step = r.buf[r.pos++];
            if (step > 7) r.corrupt();
            c += d8_dc[step], row += d8_dr[step];
            if (c < 0 || row < 0 || c >= db.cols || row >= db.rows) r.corrupt();
        }
        float z;
        std::memcpy(&z, r.buf.data() + r.pos, 4);
        r.pos += 4;
        const glm::vec2 xy = affine_node_xy(pos.nodes, db.origin, c, row);
        out[k] = {xy.x, xy.y, z, 0.0f};
    }
}

// One branch record (first from the running count `next`); on grid nodes its head cell from the
// running `head`.
DvBranch get_record(Reader& r, const DrainageDb& db, std::size_t id, std::uint64_t next, bool grid, std::uint64_t& head) {
    const std::size_t nb = db.branches.size();
    DvBranch b{};
    b.first = std::uint32_t(next);
    const std::uint64_t count = r.varint(), link = r.varint();
    const std::int64_t step = (link & 1) ? -std::int64_t((link + 1) >> 1) : std::int64_t(link >> 1);
    const std::int64_t down = link ? std::int64_t(id) + step : -1;
    if (count > 0xffffffffu || down < -1 || down >= std::int64_t(nb) || count < 1u + (down >= 0)) r.corrupt();
    if (count > db.vertices.size() - next) r.corrupt();
    b.count = std::uint32_t(count), b.downstream = std::int32_t(down);
    b.order = r.get<std::uint8_t>();
    const std::uint64_t basin = r.varint(), head_acc = r.varint();
    if (basin > 0xffffffffu || head_acc > 0xffffffffu) r.corrupt();
    b.basin = std::uint32_t(basin), b.head_acc = std::uint32_t(head_acc);
    if (grid) {
        head += r.varint();
        if (head >= std::uint64_t(db.cols) * std::uint64_t(db.rows)) r.corrupt();
    }
    return b;
}

// Branches, each its record then its stored vertices (x, y, z or on grid nodes); upstream lists
// from the links; flow from each branch's head_acc and its basin's total; end junctions copied
// from the downstream branch's head.
void get_branches(Reader& r, DrainageDb& db, std::uint64_t upstream_count, const Positions& pos) {
    std::uint64_t next = 0, head = 0;
    for (std::size_t id = 0; id < db.branches.size(); ++id) {
        const DvBranch b = db.branches[id] = get_record(r, db, id, next, pos.grid, head);
        const std::uint32_t stored = b.count - (b.downstream >= 0);
        DvVertex* out = db.vertices.data() + b.first;
        if (pos.grid) {
            get_grid_vertices(r, db, pos, std::uint32_t(head), out, stored);
        } else {
            r.need(std::size_t(stored) * 12);
            for (std::uint32_t k = 0; k < stored; ++k, r.pos += 12) std::memcpy(&out[k], r.buf.data() + r.pos, 12);
        }
        next += b.count;
    }
    if (next != db.vertices.size()) r.corrupt();
    link_upstream(db.branches, db.upstream);
    if (db.upstream.size() != upstream_count) r.corrupt();
    std::vector<double> total;
    if (!basin_totals(db, total)) r.corrupt();
    for (const DvBranch& b : db.branches)
        for (std::uint32_t k = 0; k + (b.downstream >= 0) < b.count; ++k)
            db.vertices[b.first + k].flow = branch_flow(b, k, total);
    for (const DvBranch& b : db.branches)  // the end junction: the downstream branch's head
        if (b.downstream >= 0)
            db.vertices[b.first + b.count - 1] = db.vertices[db.branches[std::size_t(b.downstream)].first];
}

void get_divides(Reader& r, DrainageDb& db) {
    std::uint64_t next = 0;
    for (DvPolyline& p : db.divides) p.first = std::uint32_t(next), p.count = r.get<std::uint32_t>(), next += p.count;
    if (next != db.divide_vertices.size()) r.corrupt();
    r.need(db.divide_vertices.size() * 12);
    for (DvVertex& v : db.divide_vertices) {
        float xyz[3];
        std::memcpy(xyz, r.buf.data() + r.pos, 12);
        r.pos += 12;
        v = {xyz[0], xyz[1], xyz[2], 0.0f};
    }
}

void get_body(Reader& r, DrainageDb& db, Positions& pos) {
    std::uint64_t* counts = pos.counts;
    for (int k = 0; k < 5; ++k) counts[k] = r.get<std::uint64_t>();
    if (pos.from_source) return;  // nothing allocated from them: checked against the network made
    const std::size_t min_sizes[5] = {4, 5, 0, 12, 4};  // bytes each needs at least
    for (int k = 0; k < 5; ++k)
        if (counts[k] > r.buf.size() || (min_sizes[k] && counts[k] > (r.buf.size() - r.pos) / min_sizes[k] * 2))
            r.corrupt();
    db.vertices.resize(counts[0]), db.branches.resize(counts[1]);
    db.divide_vertices.resize(counts[3]), db.divides.resize(counts[4]);
    get_branches(r, db, counts[2], pos);
    get_divides(r, db);
}
std::uint64_t read_u64(const std::uint8_t* b, std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, b + at, 8);
    return v;
}

// One line set of the lines part (put_line_set), from a Reader (a whole file in memory) or a
// StreamReader (the lines part read from the file); every count checked against the bytes left
// before anything is allocated, the shape by line_set_ok. Line boxes and lengths are taken as
// stored (checking them would be a pass over every vertex; a wrong one only changes which lines
// a frame selects).
// With `vertices_at` (a StreamReader only), the vertex array is hashed but not kept: its file
// offset goes to *vertices_at and set.vertices stays empty (line_set_ok checked on the count).
// The vertex block checksums go to *block_sums when given (else they are read and dropped: the
// part's checksum covers the vertices).
template <class R>
void get_line_set(R& r, DrapedLineSet& set, std::uint64_t* vertices_at = nullptr,
                  std::vector<std::uint64_t>* block_sums = nullptr) {
    const std::uint64_t nl = r.template get<std::uint64_t>(), nv = r.template get<std::uint64_t>();
    if (nl > r.left() / (line_record_bytes + 4) || nv > r.left() / sizeof(DrapedVertex) || nl > 0xffffffffu ||
        nv > 0xffffffffu)
        r.corrupt();
    set.lines.resize(std::size_t(nl));
    std::uint64_t next = 0;
    std::vector<std::uint8_t> records;
    constexpr std::size_t per = std::size_t(1) << 16;  // records read at a time
    for (std::size_t i0 = 0; i0 < set.lines.size(); i0 += per) {
        const std::size_t n = std::min(per, set.lines.size() - i0);
        r.template array<std::uint8_t>(records, n * line_record_bytes);
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint8_t* p = records.data() + i * line_record_bytes;
            DrapedLine& l = set.lines[i0 + i];
            float box[5];
            std::memcpy(box, p, 20);
            l.lo = {box[0], box[1]}, l.hi = {box[2], box[3]}, l.length = box[4];
            std::memcpy(&l.count, p + 20, 4);
            l.order = p[24];
            l.first = std::uint32_t(next), next += l.count;
        }
    }
    if (next != nv) r.corrupt();
    if constexpr (requires { r.skip(0); }) {
        r.in_vertices = true;  // not part of the index checksum
        if (vertices_at) {
            *vertices_at = r.offset();
            r.skip(nv * sizeof(DrapedVertex));
        } else {
            r.template array<DrapedVertex>(set.vertices, nv);
        }
        r.in_vertices = false;
    } else {
        r.template array<DrapedVertex>(set.vertices, nv);
    }
    std::vector<std::uint64_t> sums;
    r.template array<std::uint64_t>(block_sums ? *block_sums : sums, vertex_blocks(nv));
    LineIndex& x = set.index;
    x.origin.x = r.template get<float>(), x.origin.y = r.template get<float>(), x.cell = r.template get<float>();
    const std::uint32_t levels = r.template get<std::uint32_t>();
    if (levels > 64) r.corrupt();
    std::uint64_t cells = 0;
    x.level_cols.resize(levels), x.level_rows.resize(levels);
    for (std::uint32_t k = 0; k < levels; ++k) {
        x.level_cols[k] = r.template get<std::uint32_t>(), x.level_rows[k] = r.template get<std::uint32_t>();
        const std::uint64_t n = std::uint64_t(x.level_cols[k]) * x.level_rows[k];  // < 2^64
        if (n > r.left() / 4 || cells + n > r.left() / 4) r.corrupt();           // 4 B a cell start
        cells += n;
    }
    r.template array<std::uint32_t>(x.start, cells + 1);
    r.template array<std::uint32_t>(x.ids, nl);
    if (!line_set_ok(set, vertices_at ? std::size_t(nv) : set.vertices.size())) r.corrupt();
}

// The lines part from the reader's position on: the fingerprint, grid and origin, which must
// agree with `db`'s when `header` is set (a whole file), then both line sets.
template <class R>
void get_lines(R& r, DrainageDb& db, bool header, std::uint64_t* vertices_at = nullptr,
               std::vector<std::uint64_t>* block_sums = nullptr, std::uint64_t* source_at = nullptr) {
    DrainageFingerprint f;
    f.file_size = r.template get<std::uint64_t>(), f.mtime_ns = r.template get<std::int64_t>();
    f.content_hash = r.template get<std::uint64_t>(), f.resample = r.template get<std::uint32_t>();
    f.options = r.template get<std::uint32_t>(), f.routing = r.template get<std::uint32_t>();
    r.template get<std::uint32_t>();
    const std::int32_t cols = r.template get<std::int32_t>(), rows = r.template get<std::int32_t>();
    const std::int32_t factor = r.template get<std::int32_t>();
    r.template get<std::uint32_t>();
    const double ox = r.template get<double>(), oy = r.template get<double>();
    if (header && !(f == db.fingerprint && cols == db.cols && rows == db.rows && factor == db.factor &&
                    ox == db.origin.x && oy == db.origin.y))
        r.corrupt();
    db.fingerprint = f, db.cols = cols, db.rows = rows, db.factor = factor, db.origin = {ox, oy};
    get_line_set(r, db.creases, vertices_at, block_sums);
    get_line_set(r, db.ridges, vertices_at ? vertices_at + 1 : nullptr, block_sums ? block_sums + 1 : nullptr);
    const std::uint64_t source_bytes = r.template get<std::uint64_t>();
    // the source's bytes, checked by its pages' checksums (not in the index checksum): left in the
    // file where a render asks for their offset
    if constexpr (requires { r.skip(0); }) {
        r.in_vertices = true;
        if (source_at) {
            if (source_bytes > r.left()) r.corrupt();
            *source_at = r.offset();
            r.skip(source_bytes);
        } else {
            r.template array<std::uint8_t>(db.crease_source, source_bytes);
        }
        r.in_vertices = false;
    } else {
        r.template array<std::uint8_t>(db.crease_source, source_bytes);
    }
    std::vector<std::uint64_t> sums;  // kept with a source left in the file (whole: the lines checksum covers it)
    r.template array<std::uint64_t>(sums, (source_bytes + crease_source_page - 1) / crease_source_page);
    if (source_at) db.crease_source_size = source_bytes, db.crease_source_sums = std::move(sums);
    // the stored creases, or the source to build them from: never both
    if (source_bytes && !db.creases.lines.empty()) r.corrupt();
    // The index checksum: a StreamReader checks it (it may not have read the vertices); a whole
    // file's lines checksum covers it.
    if constexpr (requires { r.index.digest(); }) {
        const std::uint64_t want = r.index.digest();
        if (r.template get<std::uint64_t>() != want) r.corrupt();
    } else {
        r.template get<std::uint64_t>();
    }
}

// The lines part read straight from the file into the arrays it fills, hashed as it is read
// (hash64 over the concatenation: whole 8-byte words, the last bytes one by one).
struct StreamReader {
    std::FILE* in;
    std::uint64_t remaining;  // bytes of the part not yet read (its checksum excluded)
    std::uint64_t at;         // file offset of the next byte
    std::string path;
    bool seek_vertices = false;  // skip() seeks past the vertex arrays instead of reading them
    ConcatHash part;             // every byte read (the lines checksum's)
    ConcatHash index;            // every byte read but the vertex arrays (the index checksum's)
    bool in_vertices = false;

    [[noreturn]] void corrupt() const {
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    }
    std::uint64_t left() const { return remaining; }
    void read(void* dst, std::size_t n) {
        if (n > remaining) corrupt();
        if (std::fread(dst, 1, n, in) != n) throw Error("drainage", path, "truncated drainage database");
        part.feed(static_cast<const std::uint8_t*>(dst), n);
        if (!in_vertices) index.feed(static_cast<const std::uint8_t*>(dst), n);
        remaining -= n, at += n;
    }
    std::uint64_t offset() const { return at; }
    // n bytes of vertices passed over: sought past (seek_vertices), or read and hashed in 4 MiB
    // chunks through one buffer, not kept.
    void skip(std::uint64_t n) {
        if (n > remaining) corrupt();
        if (seek_vertices) {
            if (std::fseek(in, long(at + n), SEEK_SET) != 0) throw Error("drainage", path, "truncated drainage database");
            remaining -= n, at += n;
            return;
        }
        constexpr std::size_t chunk = std::size_t(4) << 20;
        std::vector<std::uint8_t> buf(std::size_t(std::min<std::uint64_t>(n, chunk)));
        while (n > 0) {
            const std::size_t k = std::size_t(std::min<std::uint64_t>(n, chunk));
            read(buf.data(), k);
            n -= k;
        }
    }
    template <class T> T get() {
        T v;
        read(&v, sizeof(T));
        return v;
    }
    template <class T, class V> void array(V& out, std::uint64_t n) {
        if (n > remaining / sizeof(T)) corrupt();
        out.resize(std::size_t(n));
        if (n) read(out.data(), std::size_t(n) * sizeof(T));
    }
    std::uint64_t digest() const { return part.digest(); }
};

[[noreturn]] void truncated(const std::string& path) { throw Error("drainage", path, "truncated drainage database"); }

// The prefix: magic and version checked; the total length and the lines part's offset, which
// must fit a file of `size` bytes.
void check_prefix(const std::uint8_t* b, std::size_t size, const std::string& path, std::uint64_t& total,
                  std::uint64_t& lines_at) {
    if (size < 8 || std::memcmp(b, magic, 8) != 0) throw Error("drainage", path, "not a drainage database (bad magic)");
    if (size < prefix_bytes) truncated(path);
    std::uint32_t version;
    std::memcpy(&version, b + 8, 4);
    if (version != drainage_db_version)
        throw Error("drainage", path,
                    "unsupported drainage database version " + std::to_string(version) + " (expected " +
                        std::to_string(drainage_db_version) + ")");
    total = read_u64(b, total_length_at), lines_at = read_u64(b, lines_at_at);
    if (total < prefix_bytes + 16) truncated(path);
    if (lines_at % 8 != 0 || lines_at < prefix_bytes + 8 || lines_at > total - 8)
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
}

// The network of a file storing none (positions_source): the drainage grid and directions
// decoded from the crease source, the accumulation and basins made from the directions
// (network_of_directions), then the branches and divides as the builder traces them
// (build_branches, build_divides: the database built in memory, bit for bit). The grid must be
// the header's and the network the stored counts'; else the file is corrupt. A source whose
// heights are read from its DEM (crease_source.hpp) that does not decode: the DEM changed.
void network_from_source(DrainageDb& db, const Positions& pos, const std::string& path) {
    auto corrupt = [&] { throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)"); };
    DrainageGrid g;
    std::vector<std::uint8_t> dir;
    CreaseTileIndex index;
    if (db.crease_source.empty()) corrupt();
    if (!decode_crease_source(db.crease_source.data(), db.crease_source.size(), g, dir, index)) {
        if (!crease_source_dem(db.crease_source.data(), db.crease_source.size()).empty())  // its heights are the DEM's
            throw Error("drainage", path, "drainage database is stale (DEM changed)");
        corrupt();
    }
    if (g.cols != db.cols || g.rows != db.rows || g.factor != db.factor || g.origin != db.origin) corrupt();
    try {
        const FlowNetwork net = network_of_directions(g, dir);
        run_beside([&] { build_divides(g, net, db); }, [&] { build_branches(g, dir, net, db); });
    } catch (const Error&) {  // directions that do not drain (a cycle): not what a builder stores
        corrupt();
    }
    const std::uint64_t made[5] = {db.vertices.size(), db.branches.size(), db.upstream.size(),
                                   db.divide_vertices.size(), db.divides.size()};
    if (!std::equal(made, made + 5, pos.counts)) corrupt();
}

}  // namespace

DrainageDb decode_drainage_db(const std::vector<std::uint8_t>& b, const std::string& path) {
    std::uint64_t total, lines_at;
    check_prefix(b.data(), b.size(), path, total, lines_at);
    if (b.size() < total) truncated(path);
    const std::size_t n = std::size_t(total);
    if (b.size() != total || network_hash(b.data(), lines_at) != read_u64(b.data(), std::size_t(lines_at) - 8) ||
        lines_hash(b.data() + lines_at, n - 8 - std::size_t(lines_at), lines_at, total) != read_u64(b.data(), n - 8))
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    DrainageDb db;
    Reader r{Bytes{b.data(), std::size_t(lines_at) - 8}, 0, path};
    Positions pos;
    get_header(r, db, pos);
    get_body(r, db, pos);
    if (r.pos + 8 <= r.buf.size()) r.corrupt();  // only the padding to 8 bytes may follow
    Reader l{Bytes{b.data() + lines_at, n - 8 - std::size_t(lines_at)}, 0, path};
    get_lines(l, db, true);
    if (l.pos != l.buf.size()) l.corrupt();
    if (pos.from_source) network_from_source(db, pos, path);
    return db;
}

namespace {

// The lines part alone: the prefix, then the part read from its offset into the database's
// arrays and hashed on the way, then its checksum compared.
DrainageDb read_lines_part(std::FILE* in, std::uint64_t size, const std::string& path,
                           std::uint64_t* vertices_at = nullptr, std::vector<std::uint64_t>* block_sums = nullptr,
                           std::uint64_t* source_at = nullptr) {
    std::uint8_t prefix[prefix_bytes];
    const std::size_t got = std::fread(prefix, 1, std::size_t(std::min<std::uint64_t>(size, prefix_bytes)), in);
    std::uint64_t total, lines_at;
    check_prefix(prefix, got, path, total, lines_at);
    if (size < total) truncated(path);
    if (size != total) throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    if (std::fseek(in, long(lines_at), SEEK_SET) != 0) truncated(path);
    StreamReader r{in, total - 8 - lines_at, lines_at, path, false, {}, {}, false};
    r.seek_vertices = vertices_at != nullptr;
    DrainageDb db;
    get_lines(r, db, false, vertices_at, block_sums, source_at);
    if (r.left() != 0) r.corrupt();
    std::uint64_t stored;
    if (std::fread(&stored, 8, 1, in) != 1) truncated(path);
    if (r.seek_vertices) return db;  // the vertices unread: the index checksum (get_lines) is the check
    std::uint64_t h = hash64(&lines_at, 8, r.digest());
    if (hash64(&total, 8, h) != stored) r.corrupt();
    return db;
}

}  // namespace

namespace {

// Opens a DV file for reading: the handle and its size (0 when unknown).
std::FILE* open_dv(const std::string& path, std::uint64_t& size) {
    std::error_code ec;
    std::FILE* in = std::filesystem::is_regular_file(path, ec) ? std::fopen(path.c_str(), "rb") : nullptr;
    if (!in) throw Error("drainage", path, "cannot open drainage database");
    size = std::filesystem::file_size(path, ec);
    if (ec) size = 0;
    return in;
}

}  // namespace

std::optional<DrainageFingerprint> peek_drainage_fingerprint(const std::string& path) {
    std::vector<std::uint8_t> head(prefix_bytes + 40);  // the prefix and the fingerprint
    try {
        std::uint64_t size = 0, total = 0, lines_at = 0;
        std::FILE* in = open_dv(path, size);
        head.resize(std::fread(head.data(), 1, head.size(), in));
        std::fclose(in);
        check_prefix(head.data(), head.size(), path, total, lines_at);
        Reader r{Bytes{head.data(), head.size()}, prefix_bytes, path};
        return get_fingerprint(r);  // (throws when the file ends before it)
    } catch (const Error&) {
        return std::nullopt;
    }
}

DrainageDb read_drainage_db(const std::string& path, const DrainageFingerprint* expected, DvParts parts) {
    std::uint64_t size = 0;
    std::FILE* in = open_dv(path, size);
    DrainageDb db;
    try {
        if (parts == DvParts::lines) {
            db = read_lines_part(in, size, path);
        } else {
            std::vector<std::uint8_t> bytes(std::size_t(size), 0);
            bytes.resize(std::fread(bytes.data(), 1, bytes.size(), in));
            db = decode_drainage_db(bytes, path);
        }
    } catch (...) {
        std::fclose(in);
        throw;
    }
    std::fclose(in);
    if (expected && !(db.fingerprint == *expected))
        throw Error("drainage", path, "drainage database is stale (DEM changed)");
    return db;
}

DrainageDb read_drainage_line_index(const std::string& path, const DrainageFingerprint* expected,
                                    DvLineVertices& vertices) {
    std::uint64_t size = 0;
    std::FILE* in = open_dv(path, size);
    std::shared_ptr<std::FILE> file(in, [](std::FILE* f) { std::fclose(f); });
    std::uint64_t at[2] = {0, 0}, source_at = 0;
    DrainageDb db = read_lines_part(in, size, path, at, vertices.block_sums, &source_at);
    if (expected && !(db.fingerprint == *expected))
        throw Error("drainage", path, "drainage database is stale (DEM changed)");
    if (db.crease_source_size) {  // left in the file: its pages read where a frame needs them
        try {
            db.crease_source_pages = std::make_shared<const CheckedBlocks>(
                ::fileno(in), path, std::vector<CheckedBlocks::Array>{{source_at, db.crease_source_size}},
                crease_source_page, db.crease_source_sums);
        } catch (const std::bad_alloc&) {
            throw Error("drainage", path, "drainage database too large for memory");
        }
    }
    vertices.file = std::move(file), vertices.path = path;
    vertices.at[0] = at[0], vertices.at[1] = at[1];
    vertices.count[0] = db.creases.lines.empty() ? 0 : db.creases.lines.back().first + db.creases.lines.back().count;
    vertices.count[1] = db.ridges.lines.empty() ? 0 : db.ridges.lines.back().first + db.ridges.lines.back().count;
    for (int s = 0; s < 2; ++s)
        if (vertices.block_sums[s].size() != vertex_blocks(vertices.count[s]))
            throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    vertices.checked = std::make_shared<std::vector<std::atomic<bool>>>(vertices.block_sums[0].size() +
                                                                        vertices.block_sums[1].size());
    return db;
}

namespace {

// n bytes at `from` of the file into dst; false when the file ends first.
bool pread_all(std::FILE* file, char* dst, std::uint64_t n, std::uint64_t from) {
    while (n > 0) {
        const ssize_t got = ::pread(::fileno(file), dst, std::size_t(std::min<std::uint64_t>(n, 1u << 30)), off_t(from));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        dst += got, from += std::uint64_t(got), n -= std::uint64_t(got);
    }
    return true;
}

}  // namespace

void DvLineVertices::read(int set, std::uint64_t first, std::uint64_t n, DrapedVertex* out) const {
    if (!file || !checked || set < 0 || set > 1 || first > count[set] || n > count[set] - first)
        throw Error("drainage", path, "drainage line vertices out of range", ExitCode::internal);
    auto corrupt = [&] { throw DvCorrupt("drainage", path, "drainage database checksum mismatch (file corrupt)"); };
    if (n == 0) return;
    const std::size_t offset = set == 0 ? 0 : block_sums[0].size();  // set's first entry in `checked`
    std::vector<DrapedVertex> block;
    for (std::uint64_t k = first / vertex_block, last = (first + n - 1) / vertex_block; k <= last; ++k) {
        const std::uint64_t b0 = k * vertex_block, b1 = std::min(b0 + vertex_block, count[set]);
        const std::uint64_t lo = std::max(first, b0), hi = std::min(first + n, b1);  // what is wanted of it
        std::atomic<bool>& done = (*checked)[offset + std::size_t(k)];
        if (done.load(std::memory_order_acquire)) {
            if (!pread_all(file.get(), reinterpret_cast<char*>(out + (lo - first)), (hi - lo) * sizeof(DrapedVertex),
                           at[set] + lo * sizeof(DrapedVertex)))
                corrupt();
            continue;
        }
        block.resize(std::size_t(b1 - b0));
        if (!pread_all(file.get(), reinterpret_cast<char*>(block.data()), (b1 - b0) * sizeof(DrapedVertex),
                       at[set] + b0 * sizeof(DrapedVertex)) ||
            hash64(block.data(), block.size() * sizeof(DrapedVertex)) != block_sums[set][std::size_t(k)])
            corrupt();
        done.store(true, std::memory_order_release);
        std::memcpy(out + (lo - first), block.data() + (lo - b0), std::size_t(hi - lo) * sizeof(DrapedVertex));
    }
}

DrainageDb drainage_lines_only(DrainageDb db) {
    DrainageDb out;
    out.fingerprint = db.fingerprint;
    out.cols = db.cols, out.rows = db.rows, out.factor = db.factor, out.origin = db.origin;
    out.creases = std::move(db.creases), out.ridges = std::move(db.ridges);
    out.crease_source = std::move(db.crease_source), out.crease_source_sums = std::move(db.crease_source_sums);
    out.crease_source_pages = std::move(db.crease_source_pages), out.crease_source_size = db.crease_source_size;
    out.built_network = std::move(db.built_network);
    return out;
}

}  // namespace penink
