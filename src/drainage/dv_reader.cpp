// Reading DV files (layout in drainage_db.cpp): every length, count, link and basin checked
// before it is used, the checksum before anything is decoded.
#include "drainage/drainage_db.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.hpp"
#include "drainage/d8.hpp"
#include "drainage/dv_format.hpp"

namespace penink {

namespace {

using namespace dv;

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

// How the file stores vertex positions (dv_format.hpp).
struct Positions {
    bool grid = false;
    AffineNodes nodes;
};

void get_header(Reader& r, DrainageDb& db, Positions& pos) {
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
    const std::uint8_t mode = r.get<std::uint8_t>();
    if (mode != positions_explicit && mode != positions_grid) r.corrupt();
    pos.grid = mode == positions_grid;
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
    std::uint64_t counts[5];
    for (std::uint64_t& c : counts) c = r.get<std::uint64_t>();
    const std::size_t min_sizes[5] = {4, 5, 0, 12, 4};  // bytes each needs at least
    for (int k = 0; k < 5; ++k)
        if (counts[k] > r.buf.size() || (min_sizes[k] && counts[k] > (r.buf.size() - r.pos) / min_sizes[k] * 2))
            r.corrupt();
    db.vertices.resize(counts[0]), db.branches.resize(counts[1]);
    db.divide_vertices.resize(counts[3]), db.divides.resize(counts[4]);
    get_branches(r, db, counts[2], pos);
    get_divides(r, db);
}
std::uint64_t read_u64(const std::vector<std::uint8_t>& b, std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
}

}  // namespace

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
    const std::uint64_t total = read_u64(b, total_length_at);
    if (b.size() < total || total < prefix_bytes + 8)
        throw Error("drainage", path, "truncated drainage database");
    if (b.size() != total || file_hash(b.data(), b.size() - 8, total) != read_u64(b, b.size() - 8))
        throw Error("drainage", path, "drainage database checksum mismatch (file corrupt)");
    DrainageDb db;
    Reader r{b, 0, path};
    Positions pos;
    get_header(r, db, pos);
    get_body(r, db, pos);
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

}  // namespace penink
