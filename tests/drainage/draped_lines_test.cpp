// Creases and ridges draped at build time (draped_lines.hpp, dem_surface.hpp, line_set.hpp):
// the stems walked on the network are drainage_stems' vertices exactly; smoothing and draping on
// the DEM grid without a mesh give what draping the smoothed lines with TerrainLocator on
// mesh_from_terrain of the whole DEM gives, the creases on their lattice (volcano at factors 5 and 1, geographic jacksboro on
// its curvilinear UTM grid, a rotated affine grid, a grid with nodata); the line index returns exactly the lines whose box meets a query box; the build's
// progress rises monotonically through the draping stage; the network bytes of volcano do not
// depend on the lines part, and its lines part's bytes are pinned (a faster build gives the same
// lines).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/vertex_run.hpp"
#include "drainage/dem_surface.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/stems.hpp"
#include "input/dem_reader.hpp"
#include "support/synthetic_terrain.hpp"
#include "surface/surface_mesh.hpp"
#include "surface/terrain_locator.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

// The lines as a per-frame preparation drew them from the whole DEM: the index lists laid out,
// smoothed, each vertex draped with TerrainLocator on the mesh (z and PN normal; off the mesh its
// own z and a zero normal).
struct LocatorLines {
    std::vector<glm::vec3> positions, normals;
    std::vector<float> flow;
    std::vector<VertexRun> runs;
};

// The lines' runs and flow from the network's lists, their plan x, y those the build smoothed them
// to (`plan`: the smoothing is tested in fall_line_stems_test.cpp and below), draped by the
// locator.
LocatorLines locator_lines(const DvVertices& v, const std::vector<std::vector<std::uint32_t>>& lines,
                           const SurfaceMesh& mesh, const DrapedLineSet& plan) {
    LocatorLines out;
    for (const auto& line : lines) {
        out.runs.push_back({std::uint32_t(out.positions.size()), std::uint32_t(line.size())});
        for (std::uint32_t i : line) out.positions.push_back({v[i].x, v[i].y, v[i].z}), out.flow.push_back(v[i].flow);
    }
    EXPECT_EQ(plan.vertices.size(), out.positions.size());
    for (std::size_t i = 0; i < out.positions.size() && i < plan.vertices.size(); ++i)
        out.positions[i].x = plan.vertices[i].x, out.positions[i].y = plan.vertices[i].y;
    const TerrainLocator locator(mesh);
    out.normals.assign(out.positions.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < out.positions.size(); ++i) {
        SurfaceHit hit;
        if (!locator.locate(out.positions[i].x, out.positions[i].y, hit)) continue;
        glm::vec3 p;
        locator.pn_position_normal_at(hit, p, out.normals[i]);
        out.positions[i].z = p.z;
    }
    return out;
}

struct Agreement {
    std::size_t vertices = 0, exact = 0, off_surface = 0, beyond_tolerance = 0;
};

// The stored set against the locator's lines (with a lattice, each of their vertices snapped to
// it in its box: the creases'): the same runs, x, y and flow exactly; z and the normal within 1e-4 relative
// (counted); off the surface on both sides together.
Agreement compare(const DrapedLineSet& set, const LocatorLines& ref, const DrapeLattice* lattice = nullptr) {
    Agreement a;
    EXPECT_EQ(set.lines.size(), ref.runs.size());
    EXPECT_EQ(set.vertices.size(), ref.positions.size());
    if (set.vertices.size() != ref.positions.size() || set.lines.size() != ref.runs.size()) return a;
    for (std::size_t l = 0; l < set.lines.size(); ++l) {
        EXPECT_EQ(set.lines[l].first, ref.runs[l].first);
        EXPECT_EQ(set.lines[l].count, ref.runs[l].count);
    }
    for (std::size_t i = 0; i < set.vertices.size(); ++i) {
        const DrapedVertex& v = set.vertices[i];
        DrapedVertex r{ref.positions[i].x, ref.positions[i].y, ref.positions[i].z,
                       ref.normals[i].x,   ref.normals[i].y,   ref.normals[i].z, ref.flow[i]};
        if (lattice) r = snapped_vertex(r, lattice->lattice, lattice->lo, lattice->hi);
        const glm::vec3 n(v.nx, v.ny, v.nz), p(r.x, r.y, r.z), m(r.nx, r.ny, r.nz);
        ++a.vertices;
        EXPECT_EQ(v.x, p.x) << i;
        EXPECT_EQ(v.y, p.y) << i;
        EXPECT_EQ(v.flow, r.flow) << i;
        EXPECT_EQ(n == glm::vec3(0.0f), m == glm::vec3(0.0f)) << i;
        a.off_surface += n == glm::vec3(0.0f);
        if (v.z == p.z && n == m) ++a.exact;
        if (std::abs(v.z - p.z) > 1e-4f * std::max(1.0f, std::abs(p.z)) || glm::length(n - m) > 1e-4f)
            ++a.beyond_tolerance;
    }
    return a;
}

// A database built from `t` (in memory) against the locator's drape on mesh_from_terrain(t).
void expect_locator_drape(const Terrain& t, int factor, const std::string& what) {
    DrainageOptions o;
    o.resample = factor;
    const DrainageDb db = build_drainage_db(t, o);
    const SurfaceMesh mesh = mesh_from_terrain(t);
    // the creases' lattice and clamp box: every drainage vertex's
    DrapeLattice lattice{crease_lattice(resample_pn(t, drainage_resample_factor(t, o))), glm::vec2(1e30f), glm::vec2(-1e30f)};
    for (const DvVertex& v : db.vertices)
        lattice.lo = glm::min(lattice.lo, glm::vec2(v.x, v.y)), lattice.hi = glm::max(lattice.hi, glm::vec2(v.x, v.y));
    const Agreement creases =
        compare(db.creases, locator_lines(db.vertices, drainage_stems(db), mesh, db.creases), &lattice);
    const Agreement ridges = compare(db.ridges, locator_lines(db.divide_vertices, divide_polylines(db), mesh, db.ridges));
    EXPECT_GT(creases.vertices, std::size_t(db.cols) * std::size_t(db.rows) / 2) << what;
    EXPECT_GT(ridges.vertices, 0u) << what;
    EXPECT_EQ(creases.beyond_tolerance, 0u) << what;
    EXPECT_EQ(ridges.beyond_tolerance, 0u) << what;
    // the same floats: the mesh's normals, triangles and barycentric weights, found on the grid
    EXPECT_EQ(creases.exact, creases.vertices) << what;
    EXPECT_EQ(ridges.exact, ridges.vertices) << what;
    ::testing::Test::RecordProperty(what + "_crease_vertices", int(creases.vertices));
    ::testing::Test::RecordProperty(what + "_off_surface", int(creases.off_surface + ridges.off_surface));
}

TEST(DrapedLines, VolcanoDrapeEqualsTheLocatorOnTheWholeMesh) {
    const Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    expect_locator_drape(dem, 0, "volcano_factor5");
    expect_locator_drape(dem, 1, "volcano_factor1");
}

TEST(DrapedLines, GeographicDemDrapeEqualsTheLocator) {  // curvilinear UTM grid: found by walking
    const Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif");
    ASSERT_TRUE(dem.source_geographic);
    expect_locator_drape(dem, 1, "jacksboro_factor1");
}

TEST(DrapedLines, NodataAndNonAffineGridDrapeEqualsTheLocator) {
    Terrain t = terrain_from_function(70, 55, 10.0, [](double x, double y) { return rough_hills(4 * x, 4 * y) * 0.2; });
    cut_hole(t, 60.0, -40.0, 55.0);
    cut_hole(t, -200.0, 150.0, 80.0);  // on the north-west edge
    expect_locator_drape(t, 1, "holes_factor1");
    expect_locator_drape(t, 3, "holes_factor3");
}

// A DEM on a rotated affine grid (a geotransform with rotation terms): the cell under a point
// from the inverse of the node formula, on the drainage grid (nodes by the formula; normals made
// for all nodes or where asked for) and on the Terrain (stored nodes), against the locator at
// points all over and around it.
TEST(DrapedLines, RotatedAffineGridLocatesAsTheMesh) {
    Terrain t;
    t.cols = 40, t.rows = 30, t.xy_unit = 1.0;
    const double s = 25.0, a = 0.4;
    t.geotransform = {500000.0, s * std::cos(a), s * std::sin(a), 4200000.0, s * std::sin(a), -s * std::cos(a)};
    t.origin = {500300.0, 4199700.0};
    AffineNodes nodes;
    ASSERT_TRUE(terrain_affine(t, nodes));
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c) {
            const glm::vec2 xy = affine_node_xy(nodes, t.origin, c, r);
            t.pos.push_back({xy.x, xy.y, float(30.0 * std::sin(0.3 * c) * std::cos(0.2 * r) + 0.5 * c)});
            t.valid.push_back(!(c > 20 && c < 24 && r > 10 && r < 15));
        }
    const SurfaceMesh mesh = mesh_from_terrain(t);
    const TerrainLocator locator(mesh);
    const DrainageGrid g = resample_pn(t, 1);
    ASSERT_TRUE(g.has_affine);
    const DemSurface on_grid(g), on_terrain(t);
    const DemSurface on_demand(g, DemSurface::Normals::on_demand);  // each node's normal where asked for
    ASSERT_FALSE(on_demand.normals_made());
    for (std::size_t i = 0; i < g.size(); ++i) ASSERT_EQ(on_demand.node_normal(i), on_grid.normal(i)) << i;
    glm::dvec3 lo, hi;
    terrain_bounds(t, lo, hi);
    std::uint32_t h = 7;
    int hits = 0;
    for (int k = 0; k < 20000; ++k) {
        h = h * 1664525u + 1013904223u;
        const float x = float(lo.x - 30.0 + (hi.x - lo.x + 60.0) * (h >> 8) / 16777216.0);
        h = h * 1664525u + 1013904223u;
        const float y = float(lo.y - 30.0 + (hi.y - lo.y + 60.0) * (h >> 8) / 16777216.0);
        SurfaceHit want;
        const bool on = locator.locate(x, y, want);
        glm::vec3 wp, wn;
        if (on) locator.pn_position_normal_at(want, wp, wn);
        for (const DemSurface* surface : {&on_grid, &on_terrain, &on_demand}) {
            const DemDraper draper(*surface);
            int c = -1, r = -1;
            DemHit got;
            ASSERT_EQ(draper.locate(x, y, c, r, got), on) << x << " " << y;
            if (!on) continue;
            const glm::uvec3 v = mesh.tri[want.triangle];
            EXPECT_EQ(glm::uvec3(got.node[0], got.node[1], got.node[2]), v);
            EXPECT_EQ(got.bary, want.bary);
            glm::vec3 p, n;
            draper.position_normal(got, p, n);
            EXPECT_EQ(p, wp);
            EXPECT_EQ(n, wn);
        }
        hits += on;
    }
    EXPECT_GT(hits, 10000);
}

// Normals made where asked for with the faces kept between nodes (a DemDraper's): the same floats as
// those made for every node, on a grid wider and taller than the 64 x 64 cells the faces are kept
// for (slots reused) with holes, the nodes asked for in a scattered order and then row by row.
TEST(DrapedLines, NormalsFromKeptFacesAreTheNormalsOfEveryNode) {
    Terrain t = terrain_from_function(150, 131, 10.0, [](double x, double y) { return rough_hills(4 * x, 4 * y) * 0.2; });
    cut_hole(t, 60.0, -40.0, 55.0);
    cut_hole(t, -700.0, 600.0, 80.0);  // on the north-west edge
    const DrainageGrid g = resample_pn(t, 1);
    const DemSurface all(g), on_demand(g, DemSurface::Normals::on_demand);
    ASSERT_FALSE(on_demand.normals_made());
    DemSurface::FaceNormals faces;
    const auto n = std::uint32_t(g.size());
    ASSERT_EQ(std::gcd(std::uint32_t(7919), n), 1u);
    std::size_t differ = 0, holes = 0;
    for (std::uint32_t k = 0; k < 2 * n; ++k) {
        const std::uint32_t i = k < n ? std::uint32_t((std::uint64_t(k) * 7919u) % n) : k - n;  // 7919 prime to n
        const glm::vec3 got = on_demand.node_normal(int(i % std::uint32_t(g.cols)), int(i / std::uint32_t(g.cols)), faces);
        differ += got != all.normal(std::size_t(i));
        holes += !g.valid[i];
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(holes, 100u);  // the holes' edges, where faces are missing, were asked for
}

TEST(DrapedLines, StemsFromTheNetworkAreDrainageStems) {
    Terrain t = terrain_from_function(90, 70, 10.0,
                                      [](double x, double y) { return std::round(rough_hills(3 * x, 3 * y) * 0.1); });
    cut_hole(t, 100.0, 50.0, 60.0);
    for (int factor : {1, 2}) {
        DrainageGrid g = resample_pn(t, factor);
        DrainageResult res;
        const DrainageDb db = drainage_db_from_grid(g, {}, &res);
        const DrapedLineSet walked = network_stems(g, res.dir, res.net);
        const DrapedLineSet listed = listed_lines(db.vertices, drainage_stems(db));
        ASSERT_EQ(walked.lines.size(), listed.lines.size());
        EXPECT_GT(walked.lines.size(), 500u);
        EXPECT_TRUE(walked.vertices == listed.vertices);
        for (std::size_t l = 0; l < walked.lines.size(); ++l) {
            EXPECT_EQ(walked.lines[l].first, listed.lines[l].first);
            EXPECT_EQ(walked.lines[l].count, listed.lines[l].count);
        }
        // each stem's order: that of the branch it ends in (its own at a junction it joins)
        std::uint8_t top = 0;
        for (const DrapedLine& l : walked.lines) {
            top = std::max(top, l.order);
            EXPECT_GE(l.order, 1);
        }
        EXPECT_GE(top, 3);
    }
}

TEST(DrapedLines, LinesMeetingABoxAreExactlyThoseWhoseBoxMeetsIt) {
    const DrainageDb db = build_drainage_db(read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc"), DrainageOptions{});
    for (const DrapedLineSet* set : {&db.creases, &db.ridges}) {
        ASSERT_TRUE(line_set_ok(*set));
        glm::vec2 all_lo(1e30f), all_hi(-1e30f);
        for (const DrapedLine& l : set->lines) {  // boxes and 3-D lengths as the vertices give them
            glm::vec2 lo(1e30f), hi(-1e30f);
            double length = 0.0;
            for (std::uint32_t k = 0; k < l.count; ++k) {
                const DrapedVertex& v = set->vertices[l.first + k];
                lo = glm::min(lo, glm::vec2(v.x, v.y)), hi = glm::max(hi, glm::vec2(v.x, v.y));
                if (k) {
                    const DrapedVertex& u = set->vertices[l.first + k - 1];
                    const double dx = double(v.x) - u.x, dy = double(v.y) - u.y, dz = double(v.z) - u.z;
                    length += std::sqrt(dx * dx + dy * dy + dz * dz);
                }
            }
            EXPECT_EQ(l.lo, lo);
            EXPECT_EQ(l.hi, hi);
            EXPECT_EQ(l.length, float(length));
            all_lo = glm::min(all_lo, lo), all_hi = glm::max(all_hi, hi);
        }
        std::uint32_t h = 3;
        auto next = [&] {
            h = h * 1664525u + 1013904223u;
            return float(h >> 8) / 16777216.0f;
        };
        const glm::vec2 span = all_hi - all_lo;
        for (int k = 0; k < 300; ++k) {
            glm::vec2 lo = all_lo - 0.1f * span + 1.2f * span * glm::vec2(next(), next());
            glm::vec2 size = span * glm::vec2(next(), next()) * (k % 3 == 0 ? 0.05f : 0.6f);
            if (k % 7 == 0) size = glm::vec2(0.0f);  // a point
            if (k == 0) lo = all_lo, size = span;     // everything
            const glm::vec2 hi = lo + size;
            std::vector<std::uint32_t> want;
            for (std::uint32_t i = 0; i < set->lines.size(); ++i) {
                const DrapedLine& l = set->lines[i];
                if (l.lo.x <= hi.x && l.hi.x >= lo.x && l.lo.y <= hi.y && l.hi.y >= lo.y) want.push_back(i);
            }
            EXPECT_EQ(lines_meeting_box(*set, lo, hi), want) << k;
            if (k == 0) {
                EXPECT_EQ(want.size(), set->lines.size());
            }
        }
        EXPECT_TRUE(lines_meeting_box(*set, all_hi + 1.0f, all_hi + 2.0f).empty());
        EXPECT_TRUE(lines_meeting_box(*set, all_hi, all_lo).empty());  // an empty box
    }
}

struct ProgressLog {
    // a build in memory drapes both sets; one stored (the creases built by frames) the ridges
    static bool is_draping(const std::string& stage) {
        return stage == "draping creases and ridges" || stage == "draping ridges";
    }
    std::vector<std::pair<std::string, double>> steps;
    DrainageProgress callback() {
        return [this](const std::string& stage, double f) { steps.emplace_back(stage, f); };
    }
    void expect_monotone(const std::string& what) const {
        ASSERT_FALSE(steps.empty()) << what;
        EXPECT_EQ(steps.front().second, 0.0) << what;
        EXPECT_EQ(steps.back(), std::make_pair(std::string("done"), 1.0)) << what;
        bool draped = false;
        for (std::size_t i = 1; i < steps.size(); ++i) {
            EXPECT_GE(steps[i].second, steps[i - 1].second) << what << ": " << steps[i].first;
            EXPECT_LE(steps[i].second, 1.0) << what;
            draped = draped || is_draping(steps[i].first);
        }
        EXPECT_TRUE(draped) << what;
        std::size_t draping = 0;
        for (const auto& s : steps) draping += is_draping(s.first);
        EXPECT_GE(draping, 10u) << what;  // the longest stage moves on its own
        std::size_t done = 0;
        for (const auto& s : steps) done += s.second == 1.0;
        EXPECT_EQ(done, 1u) << what;
    }
};

TEST(DrapedLines, BuildProgressRisesMonotonicallyThroughDraping) {
    const fs::path d = fs::temp_directory_path() / ("penink_drape_progress_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "volcano.asc");
    Terrain dem = read_dem((d / "volcano.asc").string());
    ProgressLog in_memory, streamed, cache;
    build_drainage_db(dem, DrainageOptions{}, in_memory.callback());
    in_memory.expect_monotone("build_drainage_db");
    load_or_build_drainage((d / "volcano.asc").string(), dem, DrainageOptions{}, {}, cache.callback());
    cache.expect_monotone("load_or_build_drainage");
    Terrain copy = dem;
    build_and_write_drainage_db(copy, DrainageOptions{}, DrainageFingerprint{}, (d / "x.dv").string(),
                                streamed.callback());
    streamed.expect_monotone("build_and_write_drainage_db");
    fs::remove_all(d);
}

// The bytes of volcano's database at the automatic factor, written with an empty fingerprint.
std::vector<char> volcano_dv_bytes() {
    const fs::path d = fs::temp_directory_path() / ("penink_drape_pin_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    build_and_write_drainage_db(dem, DrainageOptions{}, DrainageFingerprint{}, (d / "v.dv").string());
    std::ifstream in(d / "v.dv", std::ios::binary);
    std::vector<char> b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    in.close();
    fs::remove_all(d);
    return b;
}

// The network part of volcano's database at the automatic factor: the bytes after the
// fingerprint, up to the network checksum, pinned by their hash (the lines part and the vertical
// exaggeration leave them alone). The file stores only the counts (the network follows from the
// crease source); the network a whole read makes again, written with its branches and divides
// (the database without its crease source), is pinned too: the bytes the file stored before.
TEST(DrapedLines, VolcanoNetworkBytesArePinned) {
    const std::vector<char> b = volcano_dv_bytes();
    ASSERT_GT(b.size(), 32u);
    constexpr std::size_t after_fingerprint = 32 + 36;
    auto network = [&](const std::uint8_t* bytes, std::size_t& n) {
        std::uint64_t lines_at = 0;
        std::memcpy(&lines_at, bytes + 24, 8);
        n = lines_at > after_fingerprint + 8 ? std::size_t(lines_at - 8 - after_fingerprint) : 0;
        return hash64(bytes + after_fingerprint, n);
    };
    std::size_t n = 0;
    EXPECT_EQ(network(reinterpret_cast<const std::uint8_t*>(b.data()), n), 0x65cfda5c93a69833ull);
    EXPECT_EQ(n, 636u);
    DrainageDb db = decode_drainage_db(std::vector<std::uint8_t>(b.begin(), b.end()), "v.dv");
    db.crease_source.clear();
    const std::vector<std::uint8_t> whole = encode_drainage_db(db);
    EXPECT_EQ(network(whole.data(), n), 0x2f2275f3fcb0b3baull);
    EXPECT_EQ(n, 1838508u);
}

// The lines build_draped_lines gives volcano at the automatic factor (build_drainage_db: every
// crease and ridge), as the lines part of its encoding holds them: the part's bytes after its
// fingerprint up to the crease source's size (0: the creases are stored), pinned by their hash: a
// change of the build that is meant to be only faster (threads, kernels, the order of work) must
// leave every crease and ridge vertex as it was (the creases on their lattice: line_lattice.hpp).
TEST(DrapedLines, VolcanoLinesBytesArePinned) {
    const Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    const std::vector<std::uint8_t> b = encode_drainage_db(build_drainage_db(dem, DrainageOptions{}));
    ASSERT_GT(b.size(), 32u);
    std::uint64_t total = 0, lines_at = 0;
    std::memcpy(&total, b.data() + 16, 8);
    std::memcpy(&lines_at, b.data() + 24, 8);
    constexpr std::size_t fingerprint = 36, source_size = 8, checksums = 16;
    ASSERT_EQ(total, b.size());
    ASSERT_GT(total, lines_at + fingerprint + source_size + checksums);
    const std::size_t n = std::size_t(total - lines_at - fingerprint - source_size - checksums);
    EXPECT_EQ(n, 4857736u);
    EXPECT_EQ(hash64(b.data() + lines_at + fingerprint, n), 0x3321abcc1b7babebull);
    std::uint64_t source = 1;
    std::memcpy(&source, b.data() + lines_at + fingerprint + n, 8);
    EXPECT_EQ(source, 0u);
}

// The lines part `penink drainage` writes for volcano at the automatic factor (the ridges and the
// creases' source, crease_source.hpp; the stems' bounds keep plan length and rise apart, the
// drape's height bound, the index by unit, the source's page checksums and the network it
// stores), pinned like the lines above.
TEST(DrapedLines, VolcanoStoredLinesBytesArePinned) {
    const std::vector<char> b = volcano_dv_bytes();
    ASSERT_GT(b.size(), 32u);
    std::uint64_t total = 0, lines_at = 0;
    std::memcpy(&total, b.data() + 16, 8);
    std::memcpy(&lines_at, b.data() + 24, 8);
    constexpr std::size_t fingerprint = 36, checksums = 16;
    ASSERT_EQ(total, b.size());
    ASSERT_GT(total, lines_at + fingerprint + checksums);
    const std::size_t n = std::size_t(total - lines_at - fingerprint - checksums);
    EXPECT_EQ(n, 690235u);
    EXPECT_EQ(hash64(b.data() + lines_at + fingerprint, n), 0x7cf868c25abd3b67ull);
}

}  // namespace
}  // namespace penink
