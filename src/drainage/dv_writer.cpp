// Writing DV files (layout in drainage_db.cpp): the bytes streamed through 4 MiB buffers that a
// second thread hashes and hands on, from a DrainageDb or any DvBranchSource; the network part,
// then the lines part, each with its checksum.
#include "drainage/drainage_db.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <future>
#include <thread>
#include <utility>

#include <unistd.h>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/dv_format.hpp"

namespace penink {

namespace {

using namespace dv;

// Output bytes in a fixed buffer; each full buffer is hashed (hash64 chained over 8-byte aligned
// chunks, so the result equals hashing the whole file at once) and handed to `out` on a second
// thread while the next one fills (one buffer in flight, so chunks stay in order).
struct Sink {
    DvBytes buf = DvBytes(std::size_t(1) << 22), spare = DvBytes(buf.size());  // unwritten until filled
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
        n -= whole, total += whole;
    }
    void room(std::size_t k) {  // at least k bytes free in buf (grown for k larger than it)
        if (n + k <= buf.size()) return;
        drain();
        if (n + k <= buf.size()) return;
        land();
        buf.resize(n + k), spare.resize(n + k);
    }
    void bytes(const void* p, std::size_t k) {
        if (k == 0) return;  // an empty array's data() may be null, which memcpy must not get
        room(k);
        std::memcpy(buf.data() + n, p, k);
        n += k;
        if (index) index->feed(static_cast<const std::uint8_t*>(p), k);
    }
    ConcatHash* index = nullptr;  // also fed every byte while set (the lines part's index checksum)
    template <class T> void put(T v) { bytes(&v, sizeof(T)); }
    std::uint64_t total = 0;  // bytes handed over so far
    // Ends the network part: zeros up to a multiple of 8 bytes, its checksum (network_hash:
    // the offset of the lines part hashed last), everything handed over and the hash started
    // afresh for the lines part. Returns that offset, which the caller writes at lines_at_at.
    std::uint64_t end_network() {
        room(16);
        while ((total + n) % 8) buf[n++] = 0;
        land();
        const std::uint64_t lines_at = total + n + 8;
        hash = hash64(buf.data(), n, hash);
        hash = hash64(&lines_at, 8, hash);
        std::memcpy(buf.data() + n, &hash, 8);
        n += 8;
        out(buf.data(), n);
        total += n, n = 0;
        hash = hash64(nullptr, 0);
        return lines_at;
    }
    // The lines part's checksum (lines_hash) appended and everything handed over; returns the
    // file's length, which the caller writes at total_length_at.
    std::uint64_t finish(std::uint64_t lines_at) {
        land();
        if (n + 16 > buf.size()) {  // no room for the hash: the full words first
            drain();
            land();
        }
        const std::uint64_t length = total + n + 8;
        hash = hash64(buf.data(), n, hash);
        hash = hash64(&lines_at, 8, hash);
        hash = hash64(&length, 8, hash);
        std::memcpy(buf.data() + n, &hash, 8);
        out(buf.data(), n + 8);
        n = 0;
        return length;
    }
};

// Where a file's two lengths go once it is written.
struct Lengths {
    std::uint64_t total = 0, lines_at = 0;
};

// The branches of a DrainageDb in the builder's shape.
class DbBranches : public DvBranchSource {
public:
    explicit DbBranches(const DrainageDb& db) : db_(db) {}
    std::size_t branch_count() const override { return db_.branches.size(); }
    std::size_t vertex_count() const override { return db_.vertices.size(); }
    std::size_t link_count() const override { return db_.upstream.size(); }
    void encode(std::size_t b0, std::size_t b1, DvBytes& out) const override {
        for (std::size_t id = b0; id < b1; ++id) {
            const DvBranch& b = db_.branches[id];
            const DvBranchRecord r{b.count, b.downstream, b.order, b.basin, b.head_acc};
            append_branch(out, r, id, false, 0, [&](std::uint8_t* p) {
                for (std::uint32_t k = 0; k < stored_count(r); ++k, p += 12)
                    std::memcpy(p, &db_.vertices[b.first + k], 12);  // x, y, z
                return p;
            });
        }
    }

private:
    const DrainageDb& db_;
};

// Branches per part of the body (made on any core, written in order).
constexpr std::size_t branches_per_part = std::size_t(1) << 15;

void put_fingerprint(Sink& w, const DrainageFingerprint& f) {
    w.put(f.file_size), w.put(f.mtime_ns), w.put(f.content_hash), w.put(f.resample), w.put(f.options), w.put(f.routing);
}

// `from_source`: the network is not stored but follows from db.crease_source (positions_source).
void put_header(Sink& w, const DrainageDb& db, const AffineNodes* grid, bool from_source) {
    w.bytes(magic, 8);
    w.put(drainage_db_version), w.put(std::uint32_t(0));
    w.put(std::uint64_t(0)), w.put(std::uint64_t(0));  // total length, lines part offset: at the end
    put_fingerprint(w, db.fingerprint);
    w.put(db.cols), w.put(db.rows), w.put(db.factor), w.put(db.origin.x), w.put(db.origin.y);
    w.put(std::uint32_t(db.crs_wkt.size()));
    w.bytes(db.crs_wkt.data(), db.crs_wkt.size());
    w.put(std::uint8_t(from_source ? positions_source : grid ? positions_grid : positions_explicit));
    if (from_source || !grid) return;
    for (double v : grid->gt) w.put(v);
    w.put(grid->unit), w.put(std::int32_t(grid->col0)), w.put(std::int32_t(grid->row0));
}

// The counts, then (unless the network follows from the crease source) branches and divides.
void put_body(Sink& w, const DrainageDb& meta, const DvBranchSource& src, bool from_source) {
    w.put(std::uint64_t(src.vertex_count())), w.put(std::uint64_t(src.branch_count()));
    w.put(std::uint64_t(src.link_count())), w.put(std::uint64_t(meta.divide_vertices.size()));
    w.put(std::uint64_t(meta.divides.size()));
    if (from_source) return;
    const std::size_t nb = src.branch_count(), parts = (nb + branches_per_part - 1) / branches_per_part;
    ordered_parts<DvBytes>(
        parts, 4,
        [&](std::size_t p, DvBytes& out) {
            out.clear();
            src.encode(p * branches_per_part, std::min(nb, (p + 1) * branches_per_part), out);
        },
        [&](const DvBytes& out) { w.bytes(out.data(), out.size()); });
    for (const DvPolyline& p : meta.divides) w.put(p.count);
    for (const DvVertex& v : meta.divide_vertices) {
        const float xyz[3] = {v.x, v.y, v.z};
        w.bytes(xyz, 12);
    }
}

// One line set: counts, line records, vertices (as they are in memory), index.
void put_line_set(Sink& w, const DrapedLineSet& set) {
    w.put(std::uint64_t(set.lines.size())), w.put(std::uint64_t(set.vertices.size()));
    for (const DrapedLine& l : set.lines) {
        const float box[5] = {l.lo.x, l.lo.y, l.hi.x, l.hi.y, l.length};
        w.bytes(box, 20);
        w.put(l.count), w.put(l.order), w.put(std::uint8_t(0)), w.put(std::uint16_t(0));
    }
    constexpr std::size_t per = std::size_t(1) << 16;  // vertices a piece, so the buffer stays 4 MiB
    ConcatHash* index = std::exchange(w.index, nullptr);  // the vertices are not in the index checksum
    for (std::size_t i = 0; i < set.vertices.size(); i += per)
        w.bytes(set.vertices.data() + i, std::min(per, set.vertices.size() - i) * sizeof(DrapedVertex));
    w.index = index;
    for (std::uint64_t k = 0; k < vertex_blocks(set.vertices.size()); ++k)
        w.put(vertex_block_hash(set.vertices.data(), set.vertices.size(), k));
    const LineIndex& x = set.index;
    w.put(x.origin.x), w.put(x.origin.y), w.put(x.cell), w.put(std::uint32_t(x.level_cols.size()));
    for (std::size_t k = 0; k < x.level_cols.size(); ++k) w.put(x.level_cols[k]), w.put(x.level_rows[k]);
    for (std::size_t i = 0; i < x.start.size(); i += per)
        w.bytes(x.start.data() + i, std::min(per, x.start.size() - i) * 4);
    for (std::size_t i = 0; i < x.ids.size(); i += per) w.bytes(x.ids.data() + i, std::min(per, x.ids.size() - i) * 4);
}

// The lines part: fingerprint (again, so it is checked alone), grid, origin, creases, ridges,
// crease source.
void put_lines(Sink& w, const DrainageDb& db) {
    ConcatHash index;
    w.index = &index;
    put_fingerprint(w, db.fingerprint);
    w.put(std::uint32_t(0));
    w.put(db.cols), w.put(db.rows), w.put(db.factor), w.put(std::uint32_t(0));
    w.put(db.origin.x), w.put(db.origin.y);
    put_line_set(w, db.creases);
    put_line_set(w, db.ridges);
    if (db.crease_source_pages)  // a source left in another file is never written
        throw Error("drainage", "", "a crease source read page by page written again", ExitCode::internal);
    w.put(std::uint64_t(db.crease_source.size()));
    w.index = nullptr;  // the source's bytes are checked by their pages' checksums
    w.bytes(db.crease_source.data(), db.crease_source.size());
    w.index = &index;
    for (const std::uint64_t sum : crease_source_page_sums(db.crease_source.data(), db.crease_source.size())) w.put(sum);
    w.index = nullptr;
    w.put(index.digest());
}

// `w` may have handed out bytes when it throws.
Lengths encode(const DrainageDb& meta, const DvBranchSource& src, Sink& w) {
    if (!line_set_ok(meta.creases) || !line_set_ok(meta.ridges))
        throw Error("drainage", "", "drainage lines are not in the shape the builder gives them", ExitCode::internal);
    Lengths l;
    const bool from_source = !meta.crease_source.empty();  // the network is the one it gives
    put_header(w, meta, src.grid_nodes(), from_source);
    put_body(w, meta, src, from_source);
    l.lines_at = w.end_network();
    put_lines(w, meta);
    l.total = w.finish(l.lines_at);
    return l;
}

Lengths encode(const DrainageDb& db, Sink& w) {
    if (!layout_ok(db))
        throw Error("drainage", "", "drainage database is not in the shape the builder gives it", ExitCode::internal);
    return encode(db, DbBranches(db), w);
}

// Streams encode_into(sink) (which returns the file's lengths) to a temp file in the same
// directory, writes the lengths into the header, then renames the file.
void write_encoded(const std::string& path, const std::function<Lengths(Sink&)>& encode_into) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    // With the system's reason (a full disk, a read-only folder: exit 2, the user can act on it).
    auto fail = [&](std::FILE* f, int err) {
        if (f) std::fclose(f);
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw Error("drainage", path,
                    "cannot write drainage database" + (err ? " (" + std::string(std::strerror(err)) + ")" : std::string()),
                    err ? ExitCode::bad_input : ExitCode::internal);
    };
    std::FILE* out = std::fopen(tmp.c_str(), "wb");
    if (!out) fail(nullptr, errno);
    bool ok = true;
    int err = 0;  // errno of the first failed call (set on the writing thread, read after it)
    {
        Sink w;
        w.out = [&](const std::uint8_t* p, std::size_t n) {
            if (ok && std::fwrite(p, 1, n, out) != n) ok = false, err = errno;
        };
        try {
            const Lengths length = encode_into(w);
            const std::uint64_t fields[2] = {length.total, length.lines_at};
            if (ok && (std::fseek(out, long(total_length_at), SEEK_SET) != 0 || std::fwrite(fields, 8, 2, out) != 2))
                ok = false, err = errno;
        } catch (...) {
            w.wait();  // the buffer in flight, before the file goes
            std::fclose(out);
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw;
        }
    }
    if (!ok) fail(out, err);
    if (std::fclose(out) != 0) fail(nullptr, errno);
    // The old file is removed first: renaming over an existing file makes ext4 (auto_da_alloc)
    // write the new one out at once, as long again as the whole build's writing. The file is
    // self-checking (length, checksum), so a crash leaving it short only costs a rebuild.
    std::error_code ec;
    std::filesystem::remove(path, ec);
    std::filesystem::rename(tmp, path, ec);
    if (ec) fail(nullptr, ec.value());
}

}  // namespace

std::vector<std::uint8_t> encode_drainage_db(const DrainageDb& db) {
    std::vector<std::uint8_t> bytes;
    Sink w;
    w.out = [&](const std::uint8_t* p, std::size_t n) { bytes.insert(bytes.end(), p, p + n); };
    const Lengths length = encode(db, w);
    std::memcpy(bytes.data() + total_length_at, &length.total, 8);
    std::memcpy(bytes.data() + lines_at_at, &length.lines_at, 8);
    return bytes;
}

void write_drainage_db(const std::string& path, const DrainageDb& db) {
    write_encoded(path, [&](Sink& w) { return encode(db, w); });
}

void write_drainage_db(const std::string& path, const DrainageDb& meta, const DvBranchSource& branches) {
    write_encoded(path, [&](Sink& w) { return encode(meta, branches, w); });
}

}  // namespace penink
