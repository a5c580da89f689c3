// DV file layout (version 5, all little-endian; compact: what the builder's invariants give is
// not stored, see layout_ok and derived_ok):
//   char[8]  magic "PNKDV\0\0\0"
//   u32      format version
//   u32      reserved (0)
//   u64      total file length in bytes (checksum included)
//   fingerprint: u64 DEM size, i64 DEM mtime (ns), u64 DEM hash, u32 resample, u32 options,
//            u32 routing
//   i32 cols, rows, factor; f64 origin easting, northing; u32 n + n bytes of CRS WKT
//   u64 counts: vertices, branches, upstream links, divide vertices, divides
//   branches: varint count; varint link: 0 for an outlet branch, else zigzag(downstream - own
//             id); u8 order; varint basin; varint head_acc (varint: LEB128, 7 bits a byte, low
//             first; zigzag: 2d for d >= 0, -2d - 1 below). first = running sum of counts;
//             upstream lists follow from the links
//   branch vertices: f32 x, y, z (12 bytes each), branch by branch, without the end junction of
//             a branch with a downstream branch (= that branch's first vertex); the flow of
//             vertex k is (head_acc + k) / the basin's total, the total being the accumulation
//             at the last vertex of the basin's outlet branch (head_acc + count - 1)
//   divides: u32 count (first = running sum); divide vertices: f32 x, y, z (flow 0)
//   u64      hash64 (FNV-1a, 64-bit words) of every byte before it
// Versions 2-4 stored each vertex's flow (16 bytes) and fixed 13-byte branches without head_acc;
// 4 added the routing.
#include "drainage/drainage_db.hpp"

#include <algorithm>
#include <bit>
#include <exception>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <future>
#include <thread>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/error.hpp"

namespace penink {

static_assert(std::endian::native == std::endian::little, "DV files are written little-endian");

namespace {

constexpr char magic[8] = {'P', 'N', 'K', 'D', 'V', 0, 0, 0};
constexpr std::size_t prefix_bytes = 8 + 4 + 4 + 8;  // magic, version, reserved, total length

// Output bytes in a fixed buffer; each full buffer is hashed (hash64 chained over 8-byte aligned
// chunks, so the result equals hashing the whole file at once) and handed to `out` on a second
// thread while the next one fills (one buffer in flight, so chunks stay in order).
struct Sink {
    std::vector<std::uint8_t> buf = std::vector<std::uint8_t>(std::size_t(1) << 22), spare = buf;
    std::size_t n = 0;
    std::uint64_t hash = hash64(nullptr, 0);
    std::function<void(const std::uint8_t*, std::size_t)> out;
    std::future<void> flight;
    ~Sink() { wait(); }
    void wait() {
        if (flight.valid()) flight.wait();
    }
    void drain() {  // hands over the whole 8-byte words, keeps the tail
        const std::size_t whole = n & ~std::size_t(7);
        if (flight.valid()) flight.get();
        std::swap(buf, spare);
        std::memcpy(buf.data(), spare.data() + whole, n - whole);
        flight = std::async(std::launch::async, [this, whole] {
            hash = hash64(spare.data(), whole, hash);
            out(spare.data(), whole);
        });
        n -= whole;
    }
    void room(std::size_t k) {  // at least k bytes free in buf (grown for k larger than it)
        if (n + k <= buf.size()) return;
        drain();
        if (n + k <= buf.size()) return;
        if (flight.valid()) flight.get();
        buf.resize(n + k), spare.resize(n + k);
    }
    void bytes(const void* p, std::size_t k) {
        room(k);
        std::memcpy(buf.data() + n, p, k);
        n += k;
    }
    template <class T> void put(T v) { bytes(&v, sizeof(T)); }
    void varint(std::uint64_t v) {
        std::uint8_t b[10];
        int k = 0;
        for (; v >= 0x80; v >>= 7) b[k++] = std::uint8_t(v | 0x80);
        b[k++] = std::uint8_t(v);
        bytes(b, std::size_t(k));
    }
    void finish() {  // hash of every byte so far, appended; everything handed over
        if (flight.valid()) flight.get();
        if (n + 8 > buf.size()) {  // a full buffer has no room for the hash
            drain();
            flight.get();
        }
        hash = hash64(buf.data(), n, hash);
        const std::uint64_t h = hash;
        std::memcpy(buf.data() + n, &h, 8);
        out(buf.data(), n + 8);
        n = 0;
    }
};

std::size_t varint_size(std::uint64_t v) { return (std::size_t(std::bit_width(v | 1)) + 6) / 7; }

struct Reader {
    const std::vector<std::uint8_t>& buf;
    std::size_t pos;
    std::string path;
    [[noreturn]] void corrupt() const {
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    }
    void need(std::size_t n) const {
        if (n > buf.size() - pos) corrupt();
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
};

// Accumulation at the outlet of basin b at total[b - 1], from the basin's outlet branch. False
// unless every basin id is in 1..outlet branches and each outlet branch has its own.
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

// Normalised flow at vertex k of branch b (as the builder's normalised_flow gives it).
float branch_flow(const DvBranch& b, std::uint32_t k, const std::vector<double>& total) {
    return float(double(std::uint64_t(b.head_acc) + k) / total[b.basin - 1]);
}

// Whether `db` has the shape drainage_db_from_grid gives it, which the compact layout relies on,
// in two checks. layout_ok (sequential, cheap; encode refuses a database failing it): branches'
// and divides' vertices consecutive, downstream links in range, basins of the outlet branches
// numbered 1..outlets. derived_ok (what is not stored; the builder's invariants, checked by
// drainage_db_canonical): a branch ending at a junction repeats the downstream branch's first
// vertex; upstream lists derived from `downstream` in branch order; divide vertices with flow 0;
// vertex flows as head_acc and the basin totals give them (branch_flow).
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

bool derived_ok(const DrainageDb& db) {
    const std::size_t nb = db.branches.size();
    std::vector<std::uint32_t> ups(nb + 1, 0);
    for (const DvBranch& b : db.branches) {
        if (b.downstream < 0) continue;
        if (!(db.vertices[b.first + b.count - 1] == db.vertices[db.branches[std::size_t(b.downstream)].first]))
            return false;
        ++ups[std::size_t(b.downstream) + 1];
    }
    for (std::size_t b = 0; b < nb; ++b) {
        ups[b + 1] += ups[b];
        if (db.branches[b].up_first != ups[b] || db.branches[b].up_count != ups[b + 1] - ups[b])
            return false;
    }
    if (db.upstream.size() != ups[nb]) return false;
    for (std::size_t b = 0; b < nb; ++b)
        if (const std::int32_t d = db.branches[b].downstream; d >= 0)
            if (db.upstream[ups[std::size_t(d)]++] != b) return false;
    for (const DvVertex& v : db.divide_vertices)
        if (v.flow != 0.0f) return false;
    std::vector<double> total;
    if (!basin_totals(db, total)) return false;
    for (const DvBranch& b : db.branches)
        for (std::uint32_t k = 0; k + (b.downstream >= 0) < b.count; ++k)
            if (db.vertices[b.first + k].flow != branch_flow(b, k, total)) return false;
    return true;
}

std::size_t header_bytes(const DrainageDb& db) {
    return prefix_bytes + 36 + 12 + 16 + 4 + db.crs_wkt.size();
}

// The branches of a DrainageDb in the builder's shape.
class DbBranches : public DvBranchSource {
public:
    explicit DbBranches(const DrainageDb& db) : db_(db) {}
    std::size_t branch_count() const override { return db_.branches.size(); }
    std::size_t vertex_count() const override { return db_.vertices.size(); }
    DvBranchRecord record(std::size_t id) const override {
        const DvBranch& b = db_.branches[id];
        return {b.count, b.downstream, b.order, b.basin, b.head_acc};
    }
    void stored_xyz(std::size_t id, std::uint8_t* out) const override {
        const DvBranch& b = db_.branches[id];
        for (std::uint32_t k = 0; k + (b.downstream >= 0) < b.count; ++k, out += 12)
            std::memcpy(out, &db_.vertices[b.first + k], 12);  // x, y, z
    }

private:
    const DrainageDb& db_;
};

std::uint32_t stored_count(const DvBranchRecord& r) { return r.count - (r.downstream >= 0); }

// The link of branch `id`: 0 at an outlet, else the zigzag of the step to its downstream branch.
std::uint64_t record_link(const DvBranchRecord& r, std::size_t id) {
    if (r.downstream < 0) return 0;
    const std::int64_t d = std::int64_t(r.downstream) - std::int64_t(id);
    return d >= 0 ? std::uint64_t(d) << 1 : (std::uint64_t(-d) << 1) - 1;
}

// Bytes of the branch records and of the vertices stored (all but repeated end junctions), and
// the number of upstream links (branches with a downstream one).
// Also the vertex bytes of the second half of the branches (from branch count / 2 on).
struct BodySize {
    std::size_t bytes = 0, links = 0, second_half = 0;
};

BodySize body_size(const DvBranchSource& src) {
    BodySize s;
    std::size_t stored = 0;
    for (std::size_t id = 0; id < src.branch_count(); ++id) {
        const DvBranchRecord r = src.record(id);
        s.bytes += varint_size(r.count) + varint_size(record_link(r, id)) + 1 + varint_size(r.basin) +
                   varint_size(r.head_acc);
        stored += stored_count(r);
        s.links += r.downstream >= 0;
        if (id == src.branch_count() / 2) s.second_half = stored - stored_count(r);
    }
    s.second_half = (stored - s.second_half) * 12;
    s.bytes += stored * 12;
    return s;
}

// The vertices of branches [b0, b1), written from `out` on.
void put_vertices(const DvBranchSource& src, std::size_t b0, std::size_t b1, std::uint8_t* out) {
    for (std::size_t id = b0; id < b1; ++id) {
        src.stored_xyz(id, out);
        out += std::size_t(stored_count(src.record(id))) * 12;
    }
}

std::size_t encoded_size(const DrainageDb& meta, const BodySize& body) {
    return header_bytes(meta) + 5 * 8 + body.bytes + meta.divides.size() * 4 + meta.divide_vertices.size() * 12 + 8;
}

void put_header(Sink& w, const DrainageDb& db, std::size_t total_bytes) {
    w.bytes(magic, 8);
    w.put(drainage_db_version), w.put(std::uint32_t(0)), w.put(std::uint64_t(total_bytes));
    const DrainageFingerprint& f = db.fingerprint;
    w.put(f.file_size), w.put(f.mtime_ns), w.put(f.content_hash), w.put(f.resample), w.put(f.options), w.put(f.routing);
    w.put(db.cols), w.put(db.rows), w.put(db.factor), w.put(db.origin.x), w.put(db.origin.y);
    w.put(std::uint32_t(db.crs_wkt.size()));
    w.bytes(db.crs_wkt.data(), db.crs_wkt.size());
}

void put_body(Sink& w, const DrainageDb& meta, const DvBranchSource& src, const BodySize& body) {
    w.put(std::uint64_t(src.vertex_count())), w.put(std::uint64_t(src.branch_count()));
    w.put(std::uint64_t(body.links)), w.put(std::uint64_t(meta.divide_vertices.size()));
    w.put(std::uint64_t(meta.divides.size()));
    for (std::size_t id = 0; id < src.branch_count(); ++id) {
        const DvBranchRecord r = src.record(id);
        w.varint(r.count), w.varint(record_link(r, id)), w.put(r.order), w.varint(r.basin), w.varint(r.head_acc);
    }
    // vertices: the second half of the branches walked on a second thread into a buffer (untouched
    // until it writes), appended after the first half
    const std::size_t nb = src.branch_count(), mid = nb / 2;
    std::vector<std::uint8_t, UninitAllocator<std::uint8_t>> second(body.second_half);
    std::exception_ptr second_error;
    std::thread walker([&] {
        try {
            put_vertices(src, mid, nb, second.data());
        } catch (...) {
            second_error = std::current_exception();
        }
    });
    try {
        for (std::size_t id = 0; id < mid; ++id) {
            const std::size_t bytes = std::size_t(stored_count(src.record(id))) * 12;
            w.room(bytes);
            src.stored_xyz(id, w.buf.data() + w.n);
            w.n += bytes;
        }
    } catch (...) {
        walker.join();
        throw;
    }
    walker.join();
    if (second_error) std::rethrow_exception(second_error);
    for (std::size_t at = 0; at < second.size(); at += std::size_t(1) << 20)
        w.bytes(second.data() + at, std::min(second.size() - at, std::size_t(1) << 20));
    for (const DvPolyline& p : meta.divides) w.put(p.count);
    for (const DvVertex& v : meta.divide_vertices) {
        const float xyz[3] = {v.x, v.y, v.z};
        w.bytes(xyz, 12);
    }
}

// `w` may have handed out bytes when it throws.
void encode(const DrainageDb& meta, const DvBranchSource& src, Sink& w) {
    const BodySize body = body_size(src);
    put_header(w, meta, encoded_size(meta, body));
    put_body(w, meta, src, body);
    w.finish();
}

void encode(const DrainageDb& db, Sink& w) {
    if (!layout_ok(db))
        throw Error("drainage", "", "drainage database is not in the shape the builder gives it", ExitCode::internal);
    encode(db, DbBranches(db), w);
}

void get_header(Reader& r, DrainageDb& db) {
    r.pos = prefix_bytes;
    DrainageFingerprint& f = db.fingerprint;
    f.file_size = r.get<std::uint64_t>(), f.mtime_ns = r.get<std::int64_t>();
    f.content_hash = r.get<std::uint64_t>(), f.resample = r.get<std::uint32_t>();
    f.options = r.get<std::uint32_t>(), f.routing = r.get<std::uint32_t>();
    db.cols = r.get<std::int32_t>(), db.rows = r.get<std::int32_t>(), db.factor = r.get<std::int32_t>();
    db.origin.x = r.get<double>(), db.origin.y = r.get<double>();
    const std::uint32_t n = r.get<std::uint32_t>();
    r.need(n);
    db.crs_wkt.assign(reinterpret_cast<const char*>(r.buf.data() + r.pos), n);
    r.pos += n;
}

// Branches: first from the running count, upstream lists from `downstream`.
void get_branches(Reader& r, DrainageDb& db, std::uint64_t upstream_count) {
    const std::size_t nb = db.branches.size();
    std::vector<std::uint32_t> ups(nb + 1, 0);
    std::uint64_t next = 0;
    for (std::size_t id = 0; id < nb; ++id) {
        DvBranch& b = db.branches[id];
        b = DvBranch{};
        b.first = std::uint32_t(next);
        const std::uint64_t count = r.varint(), link = r.varint();
        const std::int64_t step = (link & 1) ? -std::int64_t((link + 1) >> 1) : std::int64_t(link >> 1);
        const std::int64_t down = link ? std::int64_t(id) + step : -1;
        if (count > 0xffffffffu || down < -1 || down >= std::int64_t(nb) || count < 1u + (down >= 0)) r.corrupt();
        b.count = std::uint32_t(count), b.downstream = std::int32_t(down);
        b.order = r.get<std::uint8_t>();
        const std::uint64_t basin = r.varint(), head_acc = r.varint();
        if (basin > 0xffffffffu || head_acc > 0xffffffffu) r.corrupt();
        b.basin = std::uint32_t(basin), b.head_acc = std::uint32_t(head_acc);
        next += b.count;
        if (down >= 0) ++ups[std::size_t(down) + 1];
    }
    if (next != db.vertices.size()) r.corrupt();
    for (std::size_t b = 0; b < nb; ++b) {
        ups[b + 1] += ups[b];
        db.branches[b].up_first = ups[b], db.branches[b].up_count = ups[b + 1] - ups[b];
    }
    if (ups.back() != upstream_count) r.corrupt();
    db.upstream.resize(upstream_count);
    for (std::size_t b = 0; b < nb; ++b)
        if (const std::int32_t d = db.branches[b].downstream; d >= 0)
            db.upstream[ups[std::size_t(d)]++] = std::uint32_t(b);
}

// Vertices x, y, z as stored, flow from the branch's head_acc and its basin's total.
void get_vertices(Reader& r, DrainageDb& db) {
    std::vector<double> total;
    if (!basin_totals(db, total)) r.corrupt();
    for (const DvBranch& b : db.branches) {
        const std::uint32_t stored = b.count - (b.downstream >= 0);
        r.need(std::size_t(stored) * 12);
        for (std::uint32_t k = 0; k < stored; ++k) {
            float xyz[3];
            std::memcpy(xyz, r.buf.data() + r.pos, 12);
            r.pos += 12;
            db.vertices[b.first + k] = {xyz[0], xyz[1], xyz[2], branch_flow(b, k, total)};
        }
    }
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

void get_body(Reader& r, DrainageDb& db) {
    std::uint64_t counts[5];
    for (std::uint64_t& c : counts) c = r.get<std::uint64_t>();
    const std::size_t min_sizes[5] = {12, 5, 0, 12, 4};  // bytes each needs at least
    for (int k = 0; k < 5; ++k)
        if (counts[k] > r.buf.size() || (min_sizes[k] && counts[k] > (r.buf.size() - r.pos) / min_sizes[k] * 2))
            r.corrupt();
    db.vertices.resize(counts[0]), db.branches.resize(counts[1]);
    db.divide_vertices.resize(counts[3]), db.divides.resize(counts[4]);
    get_branches(r, db, counts[2]);
    get_vertices(r, db);
    get_divides(r, db);
}
std::uint64_t read_u64(const std::vector<std::uint8_t>& b, std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
}

}  // namespace

std::uint64_t hash64(const void* data, std::size_t size, std::uint64_t h) {
    constexpr std::uint64_t prime = 0x100000001b3ull;
    const auto* p = static_cast<const std::uint8_t*>(data);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        std::uint64_t w;
        std::memcpy(&w, p + i, 8);
        h = (h ^ w) * prime;
    }
    for (; i < size; ++i) h = (h ^ p[i]) * prime;
    return h;
}

bool drainage_db_canonical(const DrainageDb& db) { return layout_ok(db) && derived_ok(db); }

std::vector<std::uint8_t> encode_drainage_db(const DrainageDb& db) {
    std::vector<std::uint8_t> bytes;
    Sink w;
    w.out = [&](const std::uint8_t* p, std::size_t n) { bytes.insert(bytes.end(), p, p + n); };
    encode(db, w);
    return bytes;
}
DrainageDb decode_drainage_db(const std::vector<std::uint8_t>& b, const std::string& path) {
    if (b.size() < 8 || std::memcmp(b.data(), magic, 8) != 0)
        throw Error("drainage", path, "not a drainage database (bad magic)");
    if (b.size() < prefix_bytes) throw Error("drainage", path, "truncated drainage database");
    std::uint32_t version;
    std::memcpy(&version, b.data() + 8, 4);
    if (version != drainage_db_version)
        throw Error("drainage", path,
                    "unsupported drainage database version " + std::to_string(version) +
                        " (expected " + std::to_string(drainage_db_version) + ")");
    const std::uint64_t total = read_u64(b, 16);
    if (b.size() < total || total < prefix_bytes + 8)
        throw Error("drainage", path, "truncated drainage database");
    if (b.size() != total || hash64(b.data(), b.size() - 8) != read_u64(b, b.size() - 8))
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    DrainageDb db;
    Reader r{b, 0, path};
    get_header(r, db);
    get_body(r, db);
    if (r.pos + 8 != b.size())
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    return db;
}

DrainageDb read_drainage_db(const std::string& path, const DrainageFingerprint* expected) {
    std::error_code ec;
    std::FILE* in = std::filesystem::is_regular_file(path, ec) ? std::fopen(path.c_str(), "rb") : nullptr;
    if (!in) throw Error("drainage", path, "cannot open drainage database");
    std::vector<std::uint8_t> bytes(std::size_t(std::filesystem::file_size(path, ec)));
    const std::size_t got = ec ? 0 : std::fread(bytes.data(), 1, bytes.size(), in);
    std::fclose(in);
    bytes.resize(got);
    DrainageDb db = decode_drainage_db(bytes, path);
    if (expected && !(db.fingerprint == *expected))
        throw Error("drainage", path, "drainage database is stale (DEM changed)");
    return db;
}

namespace {

// Streams encode_into(sink) to a temp file in the same directory, then renames it.
void write_encoded(const std::string& path, const std::function<void(Sink&)>& encode_into) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    auto fail = [&](std::FILE* f) {
        if (f) std::fclose(f);
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw Error("drainage", path, "cannot write drainage database", ExitCode::internal);
    };
    std::FILE* out = std::fopen(tmp.c_str(), "wb");
    if (!out) fail(nullptr);
    bool ok = true;
    {
        Sink w;
        w.out = [&](const std::uint8_t* p, std::size_t n) { ok = ok && std::fwrite(p, 1, n, out) == n; };
        try {
            encode_into(w);
        } catch (...) {
            w.wait();  // the buffer in flight, before the file goes
            std::fclose(out);
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw;
        }
    }
    if (!ok || std::fclose(out) != 0) fail(nullptr);
    // The old file is removed first: renaming over an existing file makes ext4 (auto_da_alloc)
    // write the new one out at once, as long again as the whole build's writing. The file is
    // self-checking (length, checksum), so a crash leaving it short only costs a rebuild.
    std::error_code ec;
    std::filesystem::remove(path, ec);
    std::filesystem::rename(tmp, path, ec);
    if (ec) fail(nullptr);
}

}  // namespace

void write_drainage_db(const std::string& path, const DrainageDb& db) {
    write_encoded(path, [&](Sink& w) { encode(db, w); });
}

void write_drainage_db(const std::string& path, const DrainageDb& meta, const DvBranchSource& branches) {
    write_encoded(path, [&](Sink& w) { encode(meta, branches, w); });
}

DrainageFingerprint dem_fingerprint(const std::string& dem_path, int resample) {
    namespace fs = std::filesystem;
    std::error_code ec;
    DrainageFingerprint f;
    f.file_size = fs::file_size(dem_path, ec);
    const auto mtime = fs::last_write_time(dem_path, ec);
    std::ifstream in(dem_path, std::ios::binary);
    if (ec || !in) throw Error("drainage", dem_path, "cannot read DEM file");
    f.mtime_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(mtime.time_since_epoch()).count();
    constexpr std::uint64_t mib = 1 << 20;
    std::vector<char> chunk(std::size_t(std::min(f.file_size, mib)));
    in.read(chunk.data(), std::streamsize(chunk.size()));
    f.content_hash = hash64(chunk.data(), std::size_t(in.gcount()));
    if (f.file_size > mib) {
        in.clear();
        in.seekg(std::streamoff(f.file_size - std::min(f.file_size - mib, mib)));
        in.read(chunk.data(), std::streamsize(std::min(f.file_size - mib, mib)));
        f.content_hash = hash64(chunk.data(), std::size_t(in.gcount()), f.content_hash);
    }
    f.resample = std::uint32_t(resample);
    return f;
}

}  // namespace penink
