// DV file: exact round trip, and each corruption detected with its exact error text; the cache
// next to the DEM is written, reused, rebuilt when stale and kept in memory when unwritable.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "drainage/branches.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/dv_format.hpp"
#include "drainage/line_selection.hpp"
#include "drainage/stored_creases.hpp"
#include "input/dem_reader.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

// Whether `db` has the shape drainage_db_from_grid gives it, all of which the compact layout
// relies on (drainage_db.cpp): the layout encode checks (dv::layout_ok, line_set_ok), and what is
// not stored: a branch ending at a junction repeats the downstream branch's first vertex; upstream
// lists derived from `downstream` in branch order; divide vertices with flow 0; vertex flows as
// head_acc and the basin totals give them (branch_flow). The database read back from its encoding
// is then `db` exactly.
bool drainage_db_canonical(const DrainageDb& db) {
    if (!dv::layout_ok(db) || !line_set_ok(db.creases) || !line_set_ok(db.ridges)) return false;
    for (const DvBranch& b : db.branches)
        if (b.downstream >= 0 &&
            !(db.vertices[b.first + b.count - 1] == db.vertices[db.branches[std::size_t(b.downstream)].first]))
            return false;
    DvBranches linked = db.branches;  // upstream lists as the reader derives them
    std::vector<std::uint32_t> upstream;
    link_upstream(linked, upstream);
    if (!(linked == db.branches) || upstream != db.upstream) return false;
    for (const DvVertex& v : db.divide_vertices)
        if (v.flow != 0.0f) return false;
    std::vector<double> total;
    if (!dv::basin_totals(db, total)) return false;
    for (const DvBranch& b : db.branches)
        for (std::uint32_t k = 0; k + (b.downstream >= 0) < b.count; ++k)
            if (db.vertices[b.first + k].flow != dv::branch_flow(b, k, total)) return false;
    return true;
}

fs::path temp_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("penink_dv_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

DrainageDb sample_db() {
    DrainageGrid g = make_regular_grid(5, 3, 1.0, {3, 4, 5, 4, 3, 2, 3, 4, 3, 2, 3, 4, 5, 4, 3});
    g.origin = {1750000.5, 5900000.25};
    DrainageDb db = drainage_db_from_grid(g);
    db.crs_wkt = "PROJCS[\"NZGD2000 / New Zealand Transverse Mercator 2000\"]";
    db.fingerprint = {1234, 5678, 0xdeadbeefcafef00dull, 1, 0, 1};
    return db;
}

std::vector<char> slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const fs::path& p, const std::vector<char>& b) {
    std::ofstream(p, std::ios::binary).write(b.data(), std::streamsize(b.size()));
}

std::string read_error(const fs::path& p, const DrainageFingerprint* fp = nullptr) {
    try {
        read_drainage_db(p.string(), fp);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(DvFile, RoundTripIsExact) {
    const fs::path d = temp_dir("rt");
    const DrainageDb db = sample_db();
    write_drainage_db((d / "a.dv").string(), db);
    EXPECT_FALSE(fs::exists(d / ("a.dv.tmp-" + std::to_string(::getpid()))));
    const DrainageDb back = read_drainage_db((d / "a.dv").string(), &db.fingerprint);
    EXPECT_TRUE(back == db);
    EXPECT_EQ(back.vertices.size(), 15u + db.branches.size() - 2);  // 2 outlet branches
    EXPECT_EQ(back.origin.x, 1750000.5);
    EXPECT_EQ(encode_drainage_db(back), encode_drainage_db(db));
}

// Rough ground with pits, flats and many basins: orders above 3, thousands of branches.
DrainageDb rough_db(int cols = 120, int rows = 90) {
    std::vector<float> z(std::size_t(cols) * rows);
    std::uint32_t h = 12345;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            h = h * 1664525u + 1013904223u;
            const float noise = float(h >> 28);  // 0..15: ties and pits
            z[std::size_t(r) * cols + c] = 40.0f * std::sin(c * 0.11f) * std::cos(r * 0.07f) + 0.5f * noise;
        }
    DrainageGrid g = make_regular_grid(cols, rows, 10.0, std::move(z));
    return drainage_db_from_grid(g);
}

TEST(DvFile, FlowsFromHeadAccumulationRoundTripExactly) {
    const DrainageDb db = rough_db();
    int max_order = 0;
    std::size_t outlets = 0;
    for (const DvBranch& b : db.branches) max_order = std::max(max_order, int(b.order)), outlets += b.downstream < 0;
    EXPECT_GE(max_order, 4);
    EXPECT_GT(outlets, 10u);
    EXPECT_GT(db.branches.size(), 1000u);
    const std::vector<std::uint8_t> bytes = encode_drainage_db(db);
    EXPECT_TRUE(decode_drainage_db(bytes, "rough.dv") == db);
    EXPECT_TRUE(drainage_db_canonical(db));
    DrainageDb wrong = db;  // a flow that head_acc does not give
    wrong.vertices[wrong.branches[0].first].flow *= 0.5f;
    EXPECT_FALSE(drainage_db_canonical(wrong));
    wrong = db;
    wrong.branches.back().head_acc += 1;
    EXPECT_FALSE(drainage_db_canonical(wrong));
}

TEST(DvFile, FileOfSeveralWriteBuffersRoundTrips) {  // 4 MiB buffers hashed and written in turn
    const fs::path d = temp_dir("big");
    const DrainageDb db = rough_db(1000, 800);
    write_drainage_db((d / "big.dv").string(), db);
    EXPECT_GT(fs::file_size(d / "big.dv"), std::uintmax_t(9) << 20);
    EXPECT_TRUE(read_drainage_db((d / "big.dv").string()) == db);
}

Terrain small_terrain();

// The network streamed to the file (NetworkBranches: no vertex array) gives the very bytes the
// built DrainageDb encodes to: small, rough, with nodata, resampled.
TEST(DvFile, StreamedNetworkWritesTheDatabasesBytes) {
    const fs::path d = temp_dir("stream");
    std::vector<DrainageGrid> grids;
    grids.push_back(make_regular_grid(5, 3, 1.0, {3, 4, 5, 4, 3, 2, 3, 4, 3, 2, 3, 4, 5, 4, 3}));
    DrainageGrid rough = make_regular_grid(150, 110, 10.0, std::vector<float>(150 * 110));
    std::vector<std::uint8_t> holes(rough.size(), 1);
    std::uint32_t h = 99;
    for (std::size_t i = 0; i < rough.size(); ++i) {
        h = h * 1664525u + 1013904223u;
        rough.z[i] = 30.0f * std::sin(float(i % 150) * 0.09f) + float(h >> 29) + 0.2f * float(i / 150);
        holes[i] = (h >> 8) % 50 != 0;
    }
    grids.push_back(rough);
    grids.push_back(make_regular_grid(150, 110, 10.0, rough.z, holes));
    Terrain t = small_terrain();
    grids.push_back(resample_pn(t, 3));
    for (std::size_t k = 0; k < grids.size(); ++k) {
        DrainageGrid& g = grids[k];
        DrainageResult res;
        DrainageDb db = drainage_db_from_grid(g, {}, &res);
        db.crs_wkt = "LOCAL_CS[\"test\"]", db.fingerprint = {1, 2, 3, 1, 0, 0};
        ASSERT_TRUE(drainage_db_canonical(db));
        write_drainage_db((d / "db.dv").string(), db);
        const NetworkBranches streamed(g, res.dir, res.net);
        EXPECT_EQ(streamed.branch_count(), db.branches.size());
        EXPECT_EQ(streamed.vertex_count(), db.vertices.size());
        DrainageDb meta = db;
        meta.vertices.clear(), meta.branches.clear(), meta.upstream.clear();
        write_drainage_db((d / "net.dv").string(), meta, streamed);
        EXPECT_EQ(slurp(d / "net.dv"), slurp(d / "db.dv")) << "grid " << k;
    }
}

// Bytes of a file's network part, up to the lines part's offset.
double network_bytes(const fs::path& p) {
    const std::vector<char> b = slurp(p);
    std::uint64_t lines_at = 0;
    std::memcpy(&lines_at, b.data() + 24, 8);
    return double(lines_at);
}

// On a projected DEM at factor 1 a file streamed from the network without a crease source stores
// cells (a head cell per branch, a step per vertex: 5 instead of 12 bytes) and reads back to the
// database built in memory, x and y included; the streamed build stores the creases' source
// instead of the creases, which builds them bit for bit, and no network: a whole read makes it
// again from the source, the database built in memory again.
TEST(DvFile, GridPositionsOnAnAffineDemReadBackExactly) {
    const fs::path d = temp_dir("grid");
    Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    DrainageOptions o;
    o.resample = 1;
    DrainageDb built = build_drainage_db(t, o);
    built.crs_wkt = t.crs_wkt, built.fingerprint = {7, 8, 9, 1, 0, 0};
    write_drainage_db((d / "explicit.dv").string(), built);
    {  // the network streamed, no crease source: grid cells
        DrainageGrid g = resample_pn(t, 1);
        DrainageResult res;
        drainage_db_from_grid(g, {}, &res);
        DrainageDb meta = built;
        meta.vertices.clear(), meta.branches.clear(), meta.upstream.clear();
        write_drainage_db((d / "grid.dv").string(), meta, NetworkBranches(g, res.dir, res.net));
    }
    build_and_write_drainage_db(t, o, built.fingerprint, (d / "source.dv").string());
    EXPECT_TRUE(t.pos.empty());  // released once resampled
    DrainageDb source = read_drainage_db((d / "source.dv").string());
    ASSERT_FALSE(source.crease_source.empty());
    EXPECT_TRUE(source.creases.lines.empty());
    const DrapedLineSet creases =
        StoredCreases(source.crease_source).lines_for_box(glm::vec2(-1e30f), glm::vec2(1e30f));
    ASSERT_EQ(creases.lines, built.creases.lines);
    EXPECT_EQ(std::memcmp(creases.vertices.data(), built.creases.vertices.data(),
                          sizeof(DrapedVertex) * built.creases.vertices.size()),
              0);
    source.crease_source.clear(), source.creases = built.creases;
    EXPECT_TRUE(source == built);
    EXPECT_TRUE(read_drainage_db((d / "explicit.dv").string()) == built);
    EXPECT_TRUE(read_drainage_db((d / "grid.dv").string()) == built);
    const double ratio = network_bytes(d / "grid.dv") / network_bytes(d / "explicit.dv");
    EXPECT_LT(ratio, 0.75) << network_bytes(d / "grid.dv") << " vs " << network_bytes(d / "explicit.dv");
    // header 100 + WKT + mode byte, counts 40, zeros to a multiple of 8, checksum 8
    EXPECT_EQ(network_bytes(d / "source.dv"), double((100 + built.crs_wkt.size() + 1 + 40 + 7) / 8 * 8 + 8));
    // an unknown positions mode is refused even with a matching checksum
    for (const char* name : {"grid.dv", "source.dv"}) {
        std::vector<char> b = slurp(d / name);
        const std::size_t mode_at = 100 + built.crs_wkt.size();
        ASSERT_EQ(b[mode_at], name[0] == 'g' ? 1 : 2);
        b[mode_at] = 3;
        std::uint64_t lines_at;
        std::memcpy(&lines_at, b.data() + 24, 8);
        const std::uint64_t h = dv::network_hash(reinterpret_cast<const std::uint8_t*>(b.data()), lines_at);
        std::memcpy(b.data() + lines_at - 8, &h, 8);
        spit(d / "bad.dv", b);
        EXPECT_EQ(read_error(d / "bad.dv"),
                  "penink: drainage: " + (d / "bad.dv").string() + ": drainage database checksum mismatch (file corrupt)");
    }
}

// The streamed build's file (no network stored: it follows from the crease source) reads back
// whole to the database built in memory, field by field, on volcano at its automatic factor and
// on geographic jacksboro (explicit positions); its network part is the header and counts alone.
// Damaged: a count that is not the network's, a crease source whose bytes do not decode, each
// with its checksum made to match, a short file, a flipped bit: the one-line errors.
TEST(DvFile, NetworkMadeAgainFromTheCreaseSourceEqualsTheBuilds) {
    const fs::path d = temp_dir("from_source");
    for (const char* dem : {"volcano.asc", "jacksboro.tif"}) {
        const std::string what = dem;
        Terrain t = read_dem(std::string(PENINK_SOURCE_DIR "/examples/") + dem);
        const DrainageOptions o;
        const DrainageDb built = build_drainage_db(t, o);
        ASSERT_GT(built.branches.size(), 1000u) << what;
        ASSERT_GT(built.divides.size(), 10u) << what;
        const DrainageFingerprint fp{11, 12, 13, std::uint32_t(built.factor), 0, 0};
        const fs::path p = d / (what + ".dv");
        const DrainageDb meta = build_and_write_drainage_db(t, o, fp, p.string());
        EXPECT_TRUE(meta.branches.empty() && meta.vertices.empty()) << what;
        const DrainageDb back = read_drainage_db(p.string(), &fp);
        ASSERT_FALSE(back.crease_source.empty()) << what;
        EXPECT_EQ(back.cols, built.cols) << what;
        EXPECT_EQ(back.factor, built.factor) << what;
        EXPECT_EQ(back.origin, built.origin) << what;
        EXPECT_EQ(back.crs_wkt, built.crs_wkt) << what;
        EXPECT_EQ(back.vertices.size(), built.vertices.size()) << what;
        EXPECT_EQ(std::memcmp(back.vertices.data(), built.vertices.data(), sizeof(DvVertex) * built.vertices.size()), 0)
            << what;
        EXPECT_TRUE(back.branches == built.branches) << what;
        EXPECT_EQ(back.upstream, built.upstream) << what;
        EXPECT_TRUE(back.divide_vertices == built.divide_vertices) << what;
        EXPECT_EQ(back.divides, built.divides) << what;
        EXPECT_TRUE(back.ridges == built.ridges) << what;
        EXPECT_EQ(network_bytes(p), double((100 + built.crs_wkt.size() + 1 + 40 + 7) / 8 * 8 + 8)) << what;
        // written again from what was read: the same bytes
        write_drainage_db((d / "again.dv").string(), back);
        EXPECT_EQ(slurp(d / "again.dv"), slurp(p)) << what;

        const std::vector<char> good = slurp(p);
        std::uint64_t lines_at = 0;
        std::memcpy(&lines_at, good.data() + 24, 8);
        const std::string pre = "penink: drainage: " + p.string() + ": ";
        const std::string corrupt = pre + "drainage database checksum mismatch (file corrupt)";
        std::vector<char> b = good;  // one branch more than the network has
        const std::size_t counts_at = 100 + built.crs_wkt.size() + 1;
        std::uint64_t branches;
        std::memcpy(&branches, b.data() + counts_at + 8, 8);
        EXPECT_EQ(branches, built.branches.size()) << what;
        ++branches;
        std::memcpy(b.data() + counts_at + 8, &branches, 8);
        const std::uint64_t h = dv::network_hash(reinterpret_cast<const std::uint8_t*>(b.data()), lines_at);
        std::memcpy(b.data() + lines_at - 8, &h, 8);
        spit(p, b);
        EXPECT_EQ(read_error(p), corrupt) << what;
        // the crease source's coded arrays damaged (its last bytes, the network's last block's: the
        // last of its deflate stream may be padding alone), the checksums made to match: it does
        // not decode
        b = good;
        const std::size_t n = back.crease_source.size(), pages = (n + crease_source_page - 1) / crease_source_page;
        const std::size_t sums_at = good.size() - 16 - 8 * pages, source_at = sums_at - n;
        ASSERT_EQ(std::memcmp(b.data() + source_at, back.crease_source.data(), n), 0) << what;
        for (std::size_t k = 1; k <= 4; ++k) b[sums_at - k] ^= 0x5a;
        const auto* fb = reinterpret_cast<const std::uint8_t*>(b.data());
        const std::vector<std::uint64_t> sums = crease_source_page_sums(fb + source_at, n);  // its page's checksum too
        std::memcpy(b.data() + sums_at, sums.data(), 8 * pages);
        // the index checksum: the part's bytes before it but the vertex arrays and the source
        DvLineVertices where;
        read_drainage_line_index((d / "again.dv").string(), nullptr, where);
        dv::ConcatHash index;
        std::uint64_t from = lines_at;
        for (int set = 0; set < 2; ++set) {
            index.feed(fb + from, std::size_t(where.at[set] - from));
            from = where.at[set] + sizeof(DrapedVertex) * where.count[set];
        }
        index.feed(fb + from, std::size_t(source_at - from));
        index.feed(fb + sums_at, std::size_t(good.size() - 16 - sums_at));
        const auto* lp = fb + lines_at;
        const std::uint64_t ih = index.digest();
        std::memcpy(b.data() + good.size() - 16, &ih, 8);
        const std::uint64_t total = good.size();
        const std::uint64_t lh = dv::lines_hash(lp, std::size_t(total - 8 - lines_at), lines_at, total);
        std::memcpy(b.data() + total - 8, &lh, 8);
        spit(p, b);
        EXPECT_EQ(read_error(p), corrupt) << what;
        EXPECT_EQ(read_drainage_db(p.string(), nullptr, DvParts::lines).crease_source.size(),
                  back.crease_source.size())
            << what;  // the checksums do match: only the whole read decodes the source
        b = good;
        b.resize(good.size() - 100);
        spit(p, b);
        EXPECT_EQ(read_error(p), pre + "truncated drainage database") << what;
        b = good;
        b[std::size_t(lines_at) + (good.size() - std::size_t(lines_at)) / 2] ^= 0x08;
        spit(p, b);
        EXPECT_EQ(read_error(p), corrupt) << what;
    }
    fs::remove_all(d);
}

// Bytes of a line set in the lines part: counts 16, 28 a line and a vertex, index origin, side
// and level count 16, 8 a level, 4 a cell start (+ 1) and a line id.
std::size_t line_set_bytes(const DrapedLineSet& s) {  // with a checksum per 1024 vertices
    return 16 + 28 * s.lines.size() + 28 * s.vertices.size() + 8 * ((s.vertices.size() + 1023) / 1024) + 16 +
           8 * s.index.level_cols.size() + 4 * s.index.start.size() + 4 * s.index.ids.size();
}

TEST(DvFile, CompactLayoutSizeAndShapeCheck) {
    const DrainageDb db = sample_db();
    std::size_t junction_ends = 0;
    for (const DvBranch& b : db.branches) junction_ends += b.downstream >= 0;
    ASSERT_GT(junction_ends, 0u);
    // header 100 + WKT + positions byte, counts 40, branches 5 B (count, link, order, basin,
    // head_acc: one byte each here), stored vertices 12 B, divides 4 + 12 B, zeros to a multiple
    // of 8, network hash 8; lines part: header 72, the two sets, the crease source's size 8 (and
    // none of it: the creases are stored), index hash 8, hash 8
    const std::size_t network = 100 + db.crs_wkt.size() + 1 + 40 + 5 * db.branches.size() +
                                12 * (db.vertices.size() - junction_ends) + 4 * db.divides.size() +
                                12 * db.divide_vertices.size();
    const std::size_t expect =
        (network + 7) / 8 * 8 + 8 + 72 + line_set_bytes(db.creases) + line_set_bytes(db.ridges) + 8 + 8 + 8;
    EXPECT_EQ(encode_drainage_db(db).size(), expect);
    EXPECT_EQ(db.creases.index.level_cols.size(), db.creases.index.level_rows.size());
    EXPECT_GE(db.creases.index.level_cols.size(), 1u);
    DrainageDb odd = db;  // a junction vertex that is not the downstream branch's head
    const DvBranch& b = *std::find_if(odd.branches.begin(), odd.branches.end(),
                                      [](const DvBranch& x) { return x.downstream >= 0; });
    odd.vertices[b.first + b.count - 1].z += 1.0f;
    EXPECT_TRUE(drainage_db_canonical(db));
    EXPECT_FALSE(drainage_db_canonical(odd));
    DrainageDb broken = db;  // a layout the encoding cannot hold is refused
    broken.branches[0].basin = 0;
    std::string what;
    try {
        encode_drainage_db(broken);
    } catch (const Error& e) {
        what = e.what();
    }
    EXPECT_EQ(what, "penink: drainage: drainage database is not in the shape the builder gives it");
}

TEST(DvFile, CorruptionsAreDetected) {
    const fs::path d = temp_dir("bad");
    const DrainageDb db = sample_db();
    const fs::path p = d / "x.dv";
    write_drainage_db(p.string(), db);
    const std::vector<char> good = slurp(p);
    const std::string pre = "penink: drainage: " + p.string() + ": ";

    std::vector<char> b = good;
    b[good.size() / 2] ^= 0x10;
    spit(p, b);
    EXPECT_EQ(read_error(p), pre + "drainage database checksum mismatch (file corrupt)");

    b = good;
    b.resize(good.size() - 30);
    spit(p, b);
    EXPECT_EQ(read_error(p), pre + "truncated drainage database");

    b = good;
    b[8] = 7;  // a file of the layout before the lines part
    spit(p, b);
    EXPECT_EQ(read_error(p), pre + "unsupported drainage database version 7 (expected " + std::to_string(drainage_db_version) + ")");

    b = good;
    b[0] = 'X';
    spit(p, b);
    EXPECT_EQ(read_error(p), pre + "not a drainage database (bad magic)");

    spit(p, good);
    DrainageFingerprint other = db.fingerprint;
    other.mtime_ns += 1;
    EXPECT_EQ(read_error(p, &other), pre + "drainage database is stale (DEM changed)");
    other = db.fingerprint;
    other.resample = 3;
    EXPECT_EQ(read_error(p, &other), pre + "drainage database is stale (DEM changed)");
    other = db.fingerprint;
    other.routing = 0;  // built with another routing method
    EXPECT_EQ(read_error(p, &other), pre + "drainage database is stale (DEM changed)");
    EXPECT_EQ(read_error(p, &db.fingerprint), "no error");
}

// The lines part read alone (what a render reads): the creases and ridges and the header a
// whole read gives, checked by its own checksum; a flipped bit in the network part is seen only
// by a whole read, one in the lines part by both; absurd counts with a matching checksum are
// refused before anything is allocated.
// `good` with the u64 count at byte `at` of its lines part made 2^40 and the lines checksum made
// to match, so that only the count checks can refuse it.
std::vector<char> with_huge_count(const std::vector<char>& good, std::uint64_t lines_at, std::size_t at) {
    std::vector<char> b = good;
    const std::uint64_t huge = std::uint64_t(1) << 40;
    std::memcpy(b.data() + at, &huge, 8);
    const std::uint64_t total = good.size();
    const std::uint64_t h = dv::lines_hash(reinterpret_cast<const std::uint8_t*>(b.data()) + lines_at,
                                           std::size_t(total - 8 - lines_at), lines_at, total);
    std::memcpy(b.data() + total - 8, &h, 8);
    return b;
}

TEST(DvFile, LinesPartReadAloneAndChecked) {
    const fs::path d = temp_dir("lines");
    const DrainageDb db = rough_db();
    const fs::path p = d / "x.dv";
    write_drainage_db(p.string(), db);
    EXPECT_GT(db.creases.lines.size(), 1000u);
    EXPECT_GT(db.ridges.lines.size(), 5u);
    const DrainageDb lines = read_drainage_db(p.string(), &db.fingerprint, DvParts::lines);
    EXPECT_TRUE(lines == drainage_lines_only(db));
    EXPECT_TRUE(lines.vertices.empty() && lines.branches.empty() && lines.divides.empty());
    EXPECT_EQ(lines.cols, db.cols);
    EXPECT_EQ(lines.origin, db.origin);

    const std::vector<char> good = slurp(p);
    std::uint64_t lines_at = 0;
    std::memcpy(&lines_at, good.data() + 24, 8);
    ASSERT_GT(lines_at, 200u);
    ASSERT_LT(lines_at, good.size() - 200);
    const std::string pre = "penink: drainage: " + p.string() + ": ";
    auto lines_error = [&] {
        try {
            read_drainage_db(p.string(), nullptr, DvParts::lines);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::vector<char> b = good;
    b[lines_at / 2] ^= 0x04;  // in the network part
    spit(p, b);
    EXPECT_EQ(lines_error(), "no error");
    EXPECT_EQ(read_error(p), pre + "drainage database checksum mismatch (file corrupt)");
    b = good;
    b[lines_at + (good.size() - lines_at) / 2] ^= 0x04;  // in the lines part
    spit(p, b);
    EXPECT_EQ(lines_error(), pre + "drainage database checksum mismatch (file corrupt)");
    EXPECT_EQ(read_error(p), pre + "drainage database checksum mismatch (file corrupt)");
    b = good;
    b.resize(good.size() - 1);
    spit(p, b);
    EXPECT_EQ(lines_error(), pre + "truncated drainage database");
    // the creases' line and vertex counts made huge, the lines checksum made to match
    for (const std::size_t at : {std::size_t(lines_at + 72), std::size_t(lines_at + 80)}) {
        spit(p, with_huge_count(good, lines_at, at));
        EXPECT_EQ(lines_error(), pre + "drainage database checksum mismatch (file corrupt)") << at;
        EXPECT_EQ(read_error(p), pre + "drainage database checksum mismatch (file corrupt)") << at;
    }
    // a stale file is stale to both reads
    spit(p, good);
    DrainageFingerprint other = db.fingerprint;
    other.content_hash ^= 1;
    try {
        read_drainage_db(p.string(), &other, DvParts::lines);
        ADD_FAILURE() << "stale file read";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), pre + "drainage database is stale (DEM changed)");
    }
    fs::remove_all(d);
}

// A render's read leaves the creases' source in the file too, read page by page where decoded,
// each page checked by its checksum: with a tile folder, a later process reads the units' table
// and no more when the tile files hold its stems; the creases are the whole read's; the files a
// source in memory writes are the ones a source in the file reads (the same key). A bit flipped
// in a page is found when that page is read (DvCorrupt), not before.
TEST(DvFile, CreaseSourceLeftInTheFileIsReadByThePagesNeeded) {
    const fs::path d = temp_dir("source_pages");
    Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    const DrainageFingerprint fp{11, 12, 13, 1, 0, 0};
    const fs::path p = d / "j.dv";
    build_and_write_drainage_db(t, DrainageOptions{}, fp, p.string());
    const DrainageDb whole = read_drainage_db(p.string(), &fp);
    ASSERT_GT(whole.crease_source.size(), 4 * crease_source_page);
    DvLineVertices where;
    const DrainageDb first = read_drainage_line_index(p.string(), &fp, where);
    ASSERT_TRUE(first.crease_source.empty());
    ASSERT_TRUE(first.crease_source_pages);
    EXPECT_EQ(first.crease_source_size, whole.crease_source.size());
    EXPECT_EQ(first.crease_source_pages->bytes_read(), 0u);  // nothing read yet
    const glm::vec2 lo(-1e30f), hi(1e30f);
    const DrapedLineSet want = StoredCreases(whole.crease_source).lines_for_box(lo, hi);
    ASSERT_GT(want.lines.size(), 1000u);
    const std::string tiles = (d / "tiles").string();
    EXPECT_TRUE(StoredCreases::of(first, tiles)->lines_for_box(lo, hi) == want);  // built, written
    EXPECT_EQ(first.crease_source_pages->bytes_read(), first.crease_source_size);  // the grid and directions
    const DrainageDb later = read_drainage_line_index(p.string(), &fp, where);
    const std::shared_ptr<StoredCreases> read = StoredCreases::of(later, tiles);
    EXPECT_TRUE(read->lines_for_box(lo, hi) == want);
    EXPECT_EQ(read->tiles_written(), 0u);
    EXPECT_GT(later.crease_source_pages->bytes_read(), 0u);
    EXPECT_LT(later.crease_source_pages->bytes_read(), later.crease_source_size / 4);
    StoredCreases in_memory(whole.crease_source, tiles);
    EXPECT_TRUE(in_memory.lines_for_box(lo, hi) == want);
    EXPECT_GT(in_memory.tiles_read(), 0u);
    EXPECT_EQ(in_memory.tiles_written(), 0u);

    std::vector<char> b = slurp(p);  // the source's last byte (the directions' last block) flipped
    const std::size_t n = whole.crease_source.size(), pages = (n + crease_source_page - 1) / crease_source_page;
    const std::size_t source_end = b.size() - 16 - 8 * pages;
    ASSERT_EQ(std::memcmp(b.data() + source_end - n, whole.crease_source.data(), n), 0);
    b[source_end - 1] ^= 0x21;
    spit(p, b);
    const DrainageDb damaged = read_drainage_line_index(p.string(), &fp, where);  // not read yet: not found
    EXPECT_TRUE(StoredCreases::of(damaged, tiles)->lines_for_box(lo, hi) == want);  // the files need no more
    EXPECT_THROW(StoredCreases::of(damaged)->lines_for_box(lo, hi), DvCorrupt);  // a build reads that page
    fs::remove_all(d);
}

// The render path's read of the lines part (read_drainage_line_index): the line records and
// index as the whole read gives them, no vertices read or held (they are read back from the file
// as frames need them), what it reads checked by the index checksum: a bit flipped in the
// fingerprint, a line record, the index or the checksum, a truncation, hostile counts and a stale
// fingerprint are found as by the whole read; a bit flipped in the vertex arrays is found by the
// whole read (penink drainage, DvParts) only.
TEST(DvFile, LineIndexReadLeavesVerticesInTheFileAndChecksTheRest) {
    const fs::path d = temp_dir("line_index");
    const DrainageDb db = rough_db();
    const fs::path p = d / "x.dv";
    write_drainage_db(p.string(), db);
    DvLineVertices where;
    const DrainageDb got = read_drainage_line_index(p.string(), &db.fingerprint, where);
    ASSERT_TRUE(where.file);
    DrainageDb want = drainage_lines_only(db);
    EXPECT_EQ(where.count[0], want.creases.vertices.size());
    EXPECT_EQ(where.count[1], want.ridges.vertices.size());
    DrapedVertices back(want.creases.vertices.size());
    where.read(0, 0, back.size(), back.data());
    EXPECT_TRUE(back == want.creases.vertices);
    back.resize(7);
    where.read(1, 3, 7, back.data());
    EXPECT_TRUE(std::equal(back.begin(), back.end(), want.ridges.vertices.begin() + 3));
    EXPECT_THROW(where.read(1, want.ridges.vertices.size() - 2, 3, back.data()), Error);
    want.creases.vertices.clear(), want.ridges.vertices.clear();
    EXPECT_TRUE(got == want);

    const std::vector<char> good = slurp(p);
    std::uint64_t lines_at = 0;
    std::memcpy(&lines_at, good.data() + 24, 8);
    const std::string pre = "penink: drainage: " + p.string() + ": ";
    auto index_error = [&](const DrainageFingerprint* fp = nullptr) {
        try {
            DvLineVertices v;
            read_drainage_line_index(p.string(), fp, v);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::size_t vertices[2] = {std::size_t(where.at[0]), std::size_t(where.at[1])};
    ASSERT_GT(vertices[0], lines_at);
    // the fingerprint, a crease record, the ridges' index (its last byte), the index checksum
    for (const std::size_t at : {std::size_t(lines_at + 5), std::size_t(lines_at + 88 + 28 * 3 + 2), good.size() - 17,
                                 good.size() - 9}) {
        std::vector<char> b = good;
        b[at] ^= 0x20;
        spit(p, b);
        EXPECT_EQ(index_error(), pre + "drainage database checksum mismatch (file corrupt)") << at;
        EXPECT_EQ(read_error(p), pre + "drainage database checksum mismatch (file corrupt)") << at;
    }
    for (const std::size_t at : {vertices[0], vertices[0] + where.count[0] * 28 / 2 + 3, vertices[1] + 27}) {
        std::vector<char> b = good;
        b[at] ^= 0x20;
        spit(p, b);
        EXPECT_EQ(index_error(), "no error") << at;
        EXPECT_EQ(read_error(p), pre + "drainage database checksum mismatch (file corrupt)") << at;
    }
    std::vector<char> b = good;
    b[lines_at / 2] ^= 0x04;  // the network part is not the render's
    spit(p, b);
    EXPECT_EQ(index_error(), "no error");
    b = good;
    b.resize(good.size() - 1);
    spit(p, b);
    EXPECT_EQ(index_error(), pre + "truncated drainage database");
    for (const std::size_t at : {std::size_t(lines_at + 72), std::size_t(lines_at + 80)}) {
        spit(p, with_huge_count(good, lines_at, at));
        EXPECT_EQ(index_error(), pre + "drainage database checksum mismatch (file corrupt)") << at;
    }
    spit(p, good);
    EXPECT_EQ(index_error(&db.fingerprint), "no error");
    DrainageFingerprint other = db.fingerprint;
    other.content_hash ^= 1;
    EXPECT_EQ(index_error(&other), pre + "drainage database is stale (DEM changed)");
    fs::remove_all(d);
}

// Each block of 1024 vertices carries a checksum, checked the first time a render reads from the
// block: a flipped bit in the vertices (which the index read cannot see) is found when those
// vertices are read, and only then (a block without damage reads as before); a file cut short
// after it was opened is found too. Both as DvCorrupt, which makes a selection fall back to the
// database read whole (DrainageLineSource::read_whole), never drawing the damaged vertices.
TEST(DvFile, VertexBlocksAreCheckedAsTheyAreRead) {
    const fs::path d = temp_dir("vertex_blocks");
    const DrainageDb db = rough_db();
    const fs::path p = d / "x.dv";
    write_drainage_db(p.string(), db);
    const std::vector<char> good = slurp(p);
    DvLineVertices where;
    read_drainage_line_index(p.string(), nullptr, where);
    ASSERT_GT(where.count[0], 2 * dv::vertex_block);  // damage in one block, another read clean
    ASSERT_EQ(where.block_sums[0].size(), dv::vertex_blocks(where.count[0]));
    const DrainageDb lines = drainage_lines_only(db);
    const std::uint64_t bad = dv::vertex_block + 17;  // a vertex of the second block
    for (const std::size_t byte : {std::size_t(0), std::size_t(13), std::size_t(27)}) {
        std::vector<char> b = good;
        b[std::size_t(where.at[0] + bad * sizeof(DrapedVertex)) + byte] ^= 0x08;
        spit(p, b);
        DvLineVertices v;
        read_drainage_line_index(p.string(), nullptr, v);  // the index read does not see it
        DrapedVertices out(3);
        v.read(0, 5, 3, out.data());  // the first block: clean
        EXPECT_TRUE(std::equal(out.begin(), out.end(), lines.creases.vertices.begin() + 5));
        EXPECT_THROW(v.read(0, bad - 1, 3, out.data()), DvCorrupt) << byte;
        EXPECT_THROW(v.read(0, bad, 1, out.data()), DvCorrupt) << byte;  // still, on a second read
        v.read(0, 2 * dv::vertex_block + 1, 2, out.data());  // the third block: clean
        EXPECT_TRUE(std::equal(out.begin(), out.begin() + 2, lines.creases.vertices.begin() + 2 * dv::vertex_block + 1));
    }
    {  // cut after the index was read
        spit(p, good);
        DvLineVertices v;
        read_drainage_line_index(p.string(), nullptr, v);
        fs::resize_file(p, where.at[0] + 100);
        DrapedVertices out(3);
        EXPECT_THROW(v.read(0, 2 * dv::vertex_block, 3, out.data()), DvCorrupt);
    }
    {  // a selection from the damaged file: the whole database instead, as the builder gave it
        std::vector<char> b = good;
        b[std::size_t(where.at[0] + bad * sizeof(DrapedVertex))] ^= 0x08;
        spit(p, b);
        DrainageLineSource source;
        source.db = read_drainage_line_index(p.string(), nullptr, source.vertices);
        int whole_reads = 0;
        source.read_whole = [&] { return ++whole_reads, lines; };
        LineBox box;
        box.lo = {-1e9f, -1e9f}, box.hi = {1e9f, 1e9f};
        const DrainageLineData got = prepare_drainage_lines(source, box), want = prepare_drainage_lines(lines, box);
        EXPECT_EQ(whole_reads, 1);
        const auto same = [](const ScoredLineSet& x, const ScoredLineSet& y) {  // the same vertices to draw
            return x.positions == y.positions && x.normals == y.normals && x.flow == y.flow;
        };
        EXPECT_GT(want.creases.positions.size(), 2 * dv::vertex_block);
        EXPECT_TRUE(same(got.creases, want.creases));
        EXPECT_TRUE(same(got.ridges, want.ridges));
        source.read_whole = nullptr;  // none: the error goes on
        EXPECT_THROW(prepare_drainage_lines(source, box), DvCorrupt);
    }
    fs::remove_all(d);
}

Terrain small_terrain() {
    Terrain t;
    t.cols = 6, t.rows = 5, t.origin = {500000.0, 4000000.0};
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c) {
            t.pos.emplace_back(c * 10.0f, -r * 10.0f, float((c - 3) * (c - 3) + r));
            t.valid.push_back(1);
        }
    return t;
}

TEST(DvFile, CacheNextToDemIsReusedAndRebuilt) {
    const fs::path d = temp_dir("cache");
    const fs::path dem = d / "dem.asc";
    spit(dem, std::vector<char>(100, 'a'));
    const Terrain t = small_terrain();
    std::vector<std::string> log;
    auto say = [&](const std::string& m) { log.push_back(m); };
    DrainageOptions o;
    o.resample = 2;
    const DrainageDb first = load_or_build_drainage(dem.string(), t, o, say);
    ASSERT_TRUE(fs::exists(d / "dem.asc.dv"));
    EXPECT_EQ(log.back(), "drainage: wrote " + cache_file_report((d / "dem.asc.dv").string()));
    EXPECT_EQ(first.cols, 11);
    const DrainageDb again = load_or_build_drainage(dem.string(), t, o, say);
    EXPECT_EQ(log.back(), "drainage: using cached " + cache_file_report((d / "dem.asc.dv").string()));
    EXPECT_TRUE(again == first);
    spit(dem, std::vector<char>(101, 'b'));  // the DEM changed
    load_or_build_drainage(dem.string(), t, o, say);
    EXPECT_EQ(log[log.size() - 2], "penink: drainage: " + (d / "dem.asc.dv").string() +
                                       ": drainage database is stale (DEM changed); rebuilding");
    EXPECT_EQ(log.back(), "drainage: wrote " + cache_file_report((d / "dem.asc.dv").string()));
}

// A cache whose creases' source reads its heights from the DEM (factor 1) moved with its DEM to
// another folder (the same fingerprint): the render's load uses it, the heights read at the new
// path, and its creases are the ones it gave before the move, whether read whole or as a render
// reads it (the source left in the file); a whole read of a database whose DEM is gone from the
// path it stores says it is stale.
// A fingerprint made by the caller (the terrain cache's key of the same run) is taken as it is:
// the file is not read again (a path that does not exist fingerprints), the factor and routing
// are the options'.
TEST(DvFile, GivenDemFingerprintIsNotMadeAgain) {
    const Terrain t = small_terrain();
    DrainageOptions o;
    o.resample = 2, o.routing = DrainageRouting::least_cost;
    o.dem = DrainageFingerprint{123, 456, 789};
    const DrainageFingerprint f = drainage_fingerprint("/nonexistent/penink/dem.asc", t, o);
    EXPECT_EQ(f.file_size, 123u);
    EXPECT_EQ(f.mtime_ns, 456);
    EXPECT_EQ(f.content_hash, 789u);
    EXPECT_EQ(f.resample, 2u);
    EXPECT_EQ(f.routing, std::uint32_t(DrainageRouting::least_cost));
    o.dem.reset();
    EXPECT_THROW(drainage_fingerprint("/nonexistent/penink/dem.asc", t, o), Error);
}

TEST(DvFile, CacheMovedWithItsDemIsUsed) {
    const fs::path d = temp_dir("moved");
    fs::create_directories(d / "a");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "a" / "v.asc");
    DrainageOptions o;
    o.resample = 1;
    std::vector<std::string> log;
    auto say = [&](const std::string& m) { log.push_back(m); };
    const Terrain t = read_dem((d / "a" / "v.asc").string());
    load_or_build_drainage((d / "a" / "v.asc").string(), t, o, say);
    ASSERT_TRUE(fs::exists(d / "a" / "v.asc.dv"));
    const DrainageDb whole = read_drainage_db((d / "a" / "v.asc.dv").string());
    const std::string at_a = fs::absolute(d / "a" / "v.asc").lexically_normal().string();
    EXPECT_EQ(crease_source_dem(whole.crease_source.data(), whole.crease_source.size()), at_a);
    const glm::vec2 lo(-1e9f), hi(1e9f);
    const DrapedLineSet before = StoredCreases::of(whole)->lines_for_box(lo, hi);
    ASSERT_GT(before.lines.size(), 100u);
    const auto written = fs::last_write_time(d / "a" / "v.asc.dv");
    fs::rename(d / "a", d / "b");
    const Terrain moved = read_dem((d / "b" / "v.asc").string());
    const DrainageDb at_b = load_or_build_drainage((d / "b" / "v.asc").string(), moved, o, say);
    EXPECT_EQ(log.back(), "drainage: using cached " + cache_file_report((d / "b" / "v.asc.dv").string()) +
                              " (its DEM moved from " + at_a + ")");
    EXPECT_EQ(at_b.crease_source_dem, fs::absolute(d / "b" / "v.asc").lexically_normal().string());
    EXPECT_EQ(fs::last_write_time(d / "b" / "v.asc.dv"), written);  // not written again
    const DrapedLineSet after = StoredCreases::of(at_b)->lines_for_box(lo, hi);
    EXPECT_TRUE(after.lines == before.lines && after.vertices == before.vertices);
    // the stored path read instead: its DEM is gone from there
    DrainageDb stored_path = at_b;
    stored_path.crease_source_dem.clear();
    EXPECT_THROW(StoredCreases::of(stored_path)->lines_for_box(lo, hi), Error);
    fs::rename(d / "b", d / "c");  // again, read as a render reads it (the source left in the file)
    DvLineVertices in_file;
    const DrainageDb at_c = load_or_build_drainage((d / "c" / "v.asc").string(), read_dem((d / "c" / "v.asc").string()), o,
                                                   say, {}, &in_file);
    EXPECT_EQ(log.back(), "drainage: using cached " + cache_file_report((d / "c" / "v.asc.dv").string()) +
                              " (its DEM moved from " + at_a + ")");
    const DrapedLineSet paged = StoredCreases::of(at_c)->lines_for_box(lo, hi);
    EXPECT_TRUE(paged.lines == before.lines && paged.vertices == before.vertices);
    fs::rename(d / "c", d / "b");
    fs::rename(d / "b" / "v.asc", d / "b" / "w.asc");
    EXPECT_EQ(read_error(d / "b" / "v.asc.dv"),
              "penink: drainage: " + (d / "b" / "v.asc.dv").string() + ": drainage database is stale (DEM changed)");
    fs::remove_all(d);
}

// A render that builds the database keeps the grid, directions and network it made for the first
// stems (DrainageDb::built_network, taken by StoredCreases): with the DEM gone after the build (a
// source decoded again would read its heights), the lines are those a later process builds from
// the file, and the files written the same.
TEST(DvFile, BuildsNetworkServesTheFirstStems) {
    const fs::path d = temp_dir("built_network");
    fs::create_directories(d / "a");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/jacksboro.tif", d / "a" / "j.tif");
    const std::string dem = (d / "a" / "j.tif").string();
    DrainageOptions o;
    o.resample = 1;
    DvLineVertices in_file;
    DrainageDb built = load_or_build_drainage(dem, read_dem(dem), o, {}, {}, &in_file);
    ASSERT_TRUE(built.built_network);
    EXPECT_EQ(built.built_network->g.size(), std::size_t(built.cols) * std::size_t(built.rows));
    const DrainageDb later = load_or_build_drainage(dem, read_dem(dem), o, {}, {}, &in_file);  // read from the file
    EXPECT_FALSE(later.built_network);
    const glm::vec2 lo(-1e30f), hi(1e30f);
    const DrapedLineSet want = StoredCreases::of(later)->lines_for_box(lo, hi);
    ASSERT_GT(want.lines.size(), 1000u);
    fs::rename(dem, (d / "a" / "gone.tif").string());
    EXPECT_THROW(StoredCreases::of(later)->lines_for_box(lo, hi), Error);  // decoding needs the DEM's heights
    const std::shared_ptr<StoredCreases> first = StoredCreases::take(built, (d / "tiles").string());
    EXPECT_FALSE(built.built_network);
    EXPECT_TRUE(first->lines_for_box(lo, hi) == want);
    EXPECT_GT(first->tiles_written(), 0u);
    EXPECT_TRUE(StoredCreases::of(later, (d / "tiles").string())->lines_for_box(lo, hi) == want);  // the files read
    fs::remove_all(d);
}

TEST(DvFile, UnwritableCacheBuildsInMemory) {
    const fs::path d = temp_dir("ro");
    const fs::path dem = d / "dem.asc";
    spit(dem, std::vector<char>(10, 'a'));
    fs::create_directories(d / "dem.asc.dv" / "blocker");  // a directory where the cache would go
    std::vector<std::string> log;
    DrainageOptions o;
    o.resample = 1;
    const DrainageDb db = load_or_build_drainage(dem.string(), small_terrain(), o,
                                                 [&](const std::string& m) { log.push_back(m); });
    EXPECT_EQ(db.cols, 6);
    // neither read nor replaced (a warning on stderr says so)
    EXPECT_EQ(log.back(), "penink: drainage: " + (d / "dem.asc.dv").string() + ": cannot open drainage database; rebuilding");
    EXPECT_TRUE(fs::is_directory(d / "dem.asc.dv" / "blocker"));
}

}  // namespace
}  // namespace penink
