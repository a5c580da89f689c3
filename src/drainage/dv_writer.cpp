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
        room(k);
        std::memcpy(buf.data() + n, p, k);
        n += k;
    }
    template <class T> void put(T v) { bytes(&v, sizeof(T)); }
    std::uint64_t total = 0;  // bytes handed over so far
    // The checksum (file_hash: total length hashed last) appended and everything handed over;
    // returns the file's length, which the caller writes at total_length_at.
    std::uint64_t finish() {
        land();
        if (n + 16 > buf.size()) {  // no room for the hash: the full words first
            drain();
            land();
        }
        const std::uint64_t length = total + n + 8;
        hash = hash64(buf.data(), n, hash);
        hash = hash64(&length, 8, hash);
        std::memcpy(buf.data() + n, &hash, 8);
        out(buf.data(), n + 8);
        n = 0;
        return length;
    }
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

void put_header(Sink& w, const DrainageDb& db, const AffineNodes* grid) {
    w.bytes(magic, 8);
    w.put(drainage_db_version), w.put(std::uint32_t(0)), w.put(std::uint64_t(0));  // length: at the end
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

void put_body(Sink& w, const DrainageDb& meta, const DvBranchSource& src) {
    w.put(std::uint64_t(src.vertex_count())), w.put(std::uint64_t(src.branch_count()));
    w.put(std::uint64_t(src.link_count())), w.put(std::uint64_t(meta.divide_vertices.size()));
    w.put(std::uint64_t(meta.divides.size()));
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

// `w` may have handed out bytes when it throws. Returns the file's length (to be written at
// total_length_at).
std::uint64_t encode(const DrainageDb& meta, const DvBranchSource& src, Sink& w) {
    put_header(w, meta, src.grid_nodes());
    put_body(w, meta, src);
    return w.finish();
}

std::uint64_t encode(const DrainageDb& db, Sink& w) {
    if (!layout_ok(db))
        throw Error("drainage", "", "drainage database is not in the shape the builder gives it", ExitCode::internal);
    return encode(db, DbBranches(db), w);
}

// Streams encode_into(sink) (which returns the file's length) to a temp file in the same
// directory, writes the length into the header, then renames the file.
void write_encoded(const std::string& path, const std::function<std::uint64_t(Sink&)>& encode_into) {
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
            const std::uint64_t length = encode_into(w);
            ok = ok && std::fseek(out, long(total_length_at), SEEK_SET) == 0 && std::fwrite(&length, 8, 1, out) == 1;
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
    const std::uint64_t length = encode(db, w);
    std::memcpy(bytes.data() + total_length_at, &length, 8);
    return bytes;
}

void write_drainage_db(const std::string& path, const DrainageDb& db) {
    write_encoded(path, [&](Sink& w) { return encode(db, w); });
}

void write_drainage_db(const std::string& path, const DrainageDb& meta, const DvBranchSource& branches) {
    write_encoded(path, [&](Sink& w) { return encode(meta, branches, w); });
}

}  // namespace penink
