// Writing DV files (layout in drainage_db.cpp): the bytes streamed through 4 MiB buffers that a
// second thread hashes and hands on, from a DrainageDb or any DvBranchSource.
#include "drainage/drainage_db.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <future>
#include <thread>

#include <unistd.h>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/dv_format.hpp"

namespace penink {

namespace {

using namespace dv;

// LEB128 varint of v at p (at most 10 bytes); returns the byte after it.
std::uint8_t* put_varint(std::uint8_t* p, std::uint64_t v) {
    for (; v >= 0x80; v >>= 7) *p++ = std::uint8_t(v | 0x80);
    *p++ = std::uint8_t(v);
    return p;
}

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
    void wait() {  // for the buffer in flight (its error stays in it)
        if (flight.valid()) flight.wait();
    }
    void land() {  // the buffer in flight written, its error rethrown
        if (flight.valid()) flight.get();
    }
    void drain() {  // hands over the whole 8-byte words, keeps the tail
        const std::size_t whole = n & ~std::size_t(7);
        land();
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
        land();
        buf.resize(n + k), spare.resize(n + k);
    }
    void bytes(const void* p, std::size_t k) {
        room(k);
        std::memcpy(buf.data() + n, p, k);
        n += k;
    }
    template <class T> void put(T v) { bytes(&v, sizeof(T)); }
    void finish() {  // hash of every byte so far, appended; everything handed over
        land();
        if (n + 8 > buf.size()) {  // a full buffer has no room for the hash
            drain();
            land();
        }
        hash = hash64(buf.data(), n, hash);
        const std::uint64_t h = hash;
        std::memcpy(buf.data() + n, &h, 8);
        out(buf.data(), n + 8);
        n = 0;
    }
};

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

// Bytes of branch b's stored vertices: 12 each with explicit positions; on grid nodes 4 for the
// head and 5 for each next one.
std::size_t vertex_bytes(const DvBranchRecord& r, bool grid) {
    const std::size_t n = stored_count(r);
    return grid ? (n ? 5 * n - 1 : 0) : 12 * n;
}

// Bytes of the branch records and of the vertices stored (all but repeated end junctions) and the
// number of upstream links (branches with a downstream one).
struct BodySize {
    std::size_t bytes = 0, links = 0;
};

// Branches per part of the body (its records, then its vertices, are made as one part each).
constexpr std::size_t branches_per_part = std::size_t(1) << 16;

std::size_t part_count(const DvBranchSource& src) { return (src.branch_count() + branches_per_part - 1) / branches_per_part; }

// The head cell of the branch before `id` (0 before the first): head cells are stored as deltas.
std::uint32_t head_before(const DvBranchSource& src, std::size_t id) { return id ? src.head_cell(id - 1) : 0; }

BodySize body_size(const DvBranchSource& src) {
    const bool grid = src.grid_nodes() != nullptr;
    std::vector<BodySize> part(part_count(src));
    parallel_chunks(part.size(), 1, [&](std::size_t p0, std::size_t p1) {
        for (std::size_t p = p0; p < p1; ++p) {
            const std::size_t b0 = p * branches_per_part, b1 = std::min(src.branch_count(), b0 + branches_per_part);
            std::uint32_t head = grid ? head_before(src, b0) : 0;
            BodySize& s = part[p];
            for (std::size_t id = b0; id < b1; ++id) {
                const DvBranchRecord r = src.record(id);
                s.bytes += varint_size(r.count) + varint_size(record_link(r, id)) + 1 + varint_size(r.basin) +
                           varint_size(r.head_acc) + vertex_bytes(r, grid);
                if (grid) s.bytes += varint_size(src.head_cell(id) - head), head = src.head_cell(id);
                s.links += r.downstream >= 0;
            }
        }
    });
    BodySize all;
    for (const BodySize& s : part) all.bytes += s.bytes, all.links += s.links;
    return all;
}

// The records of branches [b0, b1) to `out`.
void put_records(const DvBranchSource& src, bool grid, std::size_t b0, std::size_t b1, std::vector<std::uint8_t>& out) {
    out.resize((b1 - b0) * (5 * 10 + 1));  // at most: five varints and the order byte each
    std::uint8_t* p = out.data();
    std::uint32_t head = grid ? head_before(src, b0) : 0;
    for (std::size_t id = b0; id < b1; ++id) {
        const DvBranchRecord r = src.record(id);
        p = put_varint(p, r.count), p = put_varint(p, record_link(r, id));
        *p++ = r.order;
        p = put_varint(p, r.basin), p = put_varint(p, r.head_acc);
        if (grid) p = put_varint(p, src.head_cell(id) - head), head = src.head_cell(id);
    }
    out.resize(std::size_t(p - out.data()));
}

// The stored vertices of branches [b0, b1) to `out` (x, y, z, or steps and z on grid nodes).
void put_vertices(const DvBranchSource& src, bool grid, std::size_t b0, std::size_t b1, std::vector<std::uint8_t>& out) {
    std::size_t bytes = 0;
    for (std::size_t id = b0; id < b1; ++id) bytes += vertex_bytes(src.record(id), grid);
    out.resize(bytes);
    std::uint8_t* p = out.data();
    for (std::size_t id = b0; id < b1; ++id) {
        if (grid) src.stored_steps_z(id, p);
        else src.stored_xyz(id, p);
        p += vertex_bytes(src.record(id), grid);
    }
}

std::size_t encoded_size(const DrainageDb& meta, const DvBranchSource& src, const BodySize& body) {
    return header_bytes(meta) + positions_bytes(src.grid_nodes() != nullptr) + 5 * 8 + body.bytes +
           meta.divides.size() * 4 + meta.divide_vertices.size() * 12 + 8;
}

void put_header(Sink& w, const DrainageDb& db, const AffineNodes* grid, std::size_t total_bytes) {
    w.bytes(magic, 8);
    w.put(drainage_db_version), w.put(std::uint32_t(0)), w.put(std::uint64_t(total_bytes));
    const DrainageFingerprint& f = db.fingerprint;
    w.put(f.file_size), w.put(f.mtime_ns), w.put(f.content_hash), w.put(f.resample), w.put(f.options), w.put(f.routing);
    w.put(db.cols), w.put(db.rows), w.put(db.factor), w.put(db.origin.x), w.put(db.origin.y);
    w.put(std::uint32_t(db.crs_wkt.size()));
    w.bytes(db.crs_wkt.data(), db.crs_wkt.size());
    w.put(std::uint8_t(grid ? positions_grid : positions_explicit));
    if (!grid) return;
    for (double v : grid->gt) w.put(v);
    w.put(grid->unit), w.put(std::int32_t(grid->col0)), w.put(std::int32_t(grid->row0));
}

void put_body(Sink& w, const DrainageDb& meta, const DvBranchSource& src, const BodySize& body) {
    const bool grid = src.grid_nodes() != nullptr;
    w.put(std::uint64_t(src.vertex_count())), w.put(std::uint64_t(src.branch_count()));
    w.put(std::uint64_t(body.links)), w.put(std::uint64_t(meta.divide_vertices.size()));
    w.put(std::uint64_t(meta.divides.size()));
    // parts made on all cores, written in order: the records of each block of branches, then
    // the vertices of each block
    const std::size_t parts = part_count(src);
    ordered_parts<std::vector<std::uint8_t>>(
        2 * parts, 4,
        [&](std::size_t p, std::vector<std::uint8_t>& out) {
            const std::size_t b0 = (p % parts) * branches_per_part;
            const std::size_t b1 = std::min(src.branch_count(), b0 + branches_per_part);
            if (p < parts) put_records(src, grid, b0, b1, out);
            else put_vertices(src, grid, b0, b1, out);
        },
        [&](const std::vector<std::uint8_t>& out) { w.bytes(out.data(), out.size()); });
    for (const DvPolyline& p : meta.divides) w.put(p.count);
    for (const DvVertex& v : meta.divide_vertices) {
        const float xyz[3] = {v.x, v.y, v.z};
        w.bytes(xyz, 12);
    }
}

// `w` may have handed out bytes when it throws.
void encode(const DrainageDb& meta, const DvBranchSource& src, Sink& w) {
    const BodySize body = body_size(src);
    put_header(w, meta, src.grid_nodes(), encoded_size(meta, src, body));
    put_body(w, meta, src, body);
    w.finish();
}

void encode(const DrainageDb& db, Sink& w) {
    if (!layout_ok(db))
        throw Error("drainage", "", "drainage database is not in the shape the builder gives it", ExitCode::internal);
    encode(db, DbBranches(db), w);
}

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

std::vector<std::uint8_t> encode_drainage_db(const DrainageDb& db) {
    std::vector<std::uint8_t> bytes;
    Sink w;
    w.out = [&](const std::uint8_t* p, std::size_t n) { bytes.insert(bytes.end(), p, p + n); };
    encode(db, w);
    return bytes;
}

void write_drainage_db(const std::string& path, const DrainageDb& db) {
    write_encoded(path, [&](Sink& w) { encode(db, w); });
}

void write_drainage_db(const std::string& path, const DrainageDb& meta, const DvBranchSource& branches) {
    write_encoded(path, [&](Sink& w) { encode(meta, branches, w); });
}

}  // namespace penink
