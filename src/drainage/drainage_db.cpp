// DV file layout (version 1, all little-endian):
//   char[8]  magic "PNKDV\0\0\0"
//   u32      format version
//   u32      reserved (0)
//   u64      total file length in bytes (checksum included)
//   fingerprint: u64 DEM size, i64 DEM mtime (ns), u64 DEM hash, u32 resample, u32 options
//   i32 cols, rows, factor; f64 origin easting, northing; u32 n + n bytes of CRS WKT
//   u64 counts: vertices, branches, upstream links, divide vertices, divides
//   vertices: f32 x, y, z, flow; u32 basin; u8 order                      (21 bytes each)
//   branches: u32 first, count; i32 downstream; u32 up_first, up_count, basin; u8 order (25)
//   upstream: u32 branch ids
//   divide vertices as vertices; divides: u32 first, count
//   u64      hash64 (FNV-1a, 64-bit words) of every byte before it
#include "drainage/drainage_db.hpp"

#include <bit>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/error.hpp"

namespace penink {

static_assert(std::endian::native == std::endian::little, "DV files are written little-endian");

namespace {

constexpr char magic[8] = {'P', 'N', 'K', 'D', 'V', 0, 0, 0};
constexpr std::size_t prefix_bytes = 8 + 4 + 4 + 8;  // magic, version, reserved, total length

struct Writer {
    std::vector<std::uint8_t> buf;
    template <class T> void put(T v) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
        buf.insert(buf.end(), p, p + sizeof(T));
    }
    void vertex(const DvVertex& v) {
        put(v.x), put(v.y), put(v.z), put(v.flow), put(v.basin), put(v.order);
    }
};

struct Reader {
    const std::vector<std::uint8_t>& buf;
    std::size_t pos;
    std::string path;
    void need(std::size_t n) const {
        if (n > buf.size() - pos)
            throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    }
    template <class T> T get() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, buf.data() + pos, sizeof(T));
        pos += sizeof(T);
        return v;
    }
    DvVertex vertex() {
        DvVertex v;
        v.x = get<float>(), v.y = get<float>(), v.z = get<float>(), v.flow = get<float>();
        v.basin = get<std::uint32_t>(), v.order = get<std::uint8_t>();
        return v;
    }
};

void put_header(Writer& w, const DrainageDb& db) {
    w.buf.insert(w.buf.end(), magic, magic + 8);
    w.put(drainage_db_version), w.put(std::uint32_t(0)), w.put(std::uint64_t(0));
    const DrainageFingerprint& f = db.fingerprint;
    w.put(f.file_size), w.put(f.mtime_ns), w.put(f.content_hash), w.put(f.resample), w.put(f.options);
    w.put(db.cols), w.put(db.rows), w.put(db.factor), w.put(db.origin.x), w.put(db.origin.y);
    w.put(std::uint32_t(db.crs_wkt.size()));
    w.buf.insert(w.buf.end(), db.crs_wkt.begin(), db.crs_wkt.end());
}

void get_header(Reader& r, DrainageDb& db) {
    r.pos = prefix_bytes;
    DrainageFingerprint& f = db.fingerprint;
    f.file_size = r.get<std::uint64_t>(), f.mtime_ns = r.get<std::int64_t>();
    f.content_hash = r.get<std::uint64_t>(), f.resample = r.get<std::uint32_t>();
    f.options = r.get<std::uint32_t>();
    db.cols = r.get<std::int32_t>(), db.rows = r.get<std::int32_t>(), db.factor = r.get<std::int32_t>();
    db.origin.x = r.get<double>(), db.origin.y = r.get<double>();
    const std::uint32_t n = r.get<std::uint32_t>();
    r.need(n);
    db.crs_wkt.assign(reinterpret_cast<const char*>(r.buf.data() + r.pos), n);
    r.pos += n;
}

void get_body(Reader& r, DrainageDb& db) {
    const std::uint64_t counts[5] = {r.get<std::uint64_t>(), r.get<std::uint64_t>(),
                                     r.get<std::uint64_t>(), r.get<std::uint64_t>(),
                                     r.get<std::uint64_t>()};
    const std::size_t sizes[5] = {21, 25, 4, 21, 8};
    for (int k = 0; k < 5; ++k)
        if (counts[k] > (r.buf.size() - r.pos) / sizes[k]) r.need(r.buf.size());
    db.vertices.resize(counts[0]);
    for (DvVertex& v : db.vertices) v = r.vertex();
    db.branches.resize(counts[1]);
    for (DvBranch& b : db.branches) {
        b.first = r.get<std::uint32_t>(), b.count = r.get<std::uint32_t>();
        b.downstream = r.get<std::int32_t>(), b.up_first = r.get<std::uint32_t>();
        b.up_count = r.get<std::uint32_t>(), b.basin = r.get<std::uint32_t>();
        b.order = r.get<std::uint8_t>();
    }
    db.upstream.resize(counts[2]);
    for (std::uint32_t& u : db.upstream) u = r.get<std::uint32_t>();
    db.divide_vertices.resize(counts[3]);
    for (DvVertex& v : db.divide_vertices) v = r.vertex();
    db.divides.resize(counts[4]);
    for (DvPolyline& p : db.divides) p.first = r.get<std::uint32_t>(), p.count = r.get<std::uint32_t>();
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

std::vector<std::uint8_t> encode_drainage_db(const DrainageDb& db) {
    Writer w;
    put_header(w, db);
    w.put(std::uint64_t(db.vertices.size())), w.put(std::uint64_t(db.branches.size()));
    w.put(std::uint64_t(db.upstream.size())), w.put(std::uint64_t(db.divide_vertices.size()));
    w.put(std::uint64_t(db.divides.size()));
    w.buf.reserve(w.buf.size() + db.vertices.size() * 21 + db.branches.size() * 29 +
                  db.divide_vertices.size() * 21 + db.divides.size() * 8 + 8);
    for (const DvVertex& v : db.vertices) w.vertex(v);
    for (const DvBranch& b : db.branches) {
        w.put(b.first), w.put(b.count), w.put(b.downstream), w.put(b.up_first);
        w.put(b.up_count), w.put(b.basin), w.put(b.order);
    }
    for (std::uint32_t u : db.upstream) w.put(u);
    for (const DvVertex& v : db.divide_vertices) w.vertex(v);
    for (const DvPolyline& p : db.divides) w.put(p.first), w.put(p.count);
    const std::uint64_t total = w.buf.size() + 8;
    std::memcpy(w.buf.data() + 16, &total, 8);
    w.put(hash64(w.buf.data(), w.buf.size()));
    return w.buf;
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
    std::ifstream in(path, std::ios::binary);
    if (!std::filesystem::is_regular_file(path, ec) || !in)
        throw Error("drainage", path, "cannot open drainage database");
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    DrainageDb db = decode_drainage_db(bytes, path);
    if (expected && !(db.fingerprint == *expected))
        throw Error("drainage", path, "drainage database is stale (DEM changed)");
    return db;
}

void write_drainage_db(const std::string& path, const DrainageDb& db) {
    const std::vector<std::uint8_t> bytes = encode_drainage_db(db);
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        out.close();
        if (!out) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw Error("drainage", path, "cannot write drainage database", ExitCode::internal);
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error("drainage", path, "cannot write drainage database", ExitCode::internal);
    }
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
