// Creases and ridges through the binary: `penink render` of volcano.asc writes `creases` and
// `ridges` layers of object-space paths, raising [creases] min_score removes lines, enabled =
// false empties the layer; the drainage cache `<DEM>.dv` is written next to the DEM, reused, and
// rebuilt when corrupt or stale; `penink drainage --rasters` writes the four GeoTIFFs.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>

#include <set>
#include <tuple>

#include <gdal_priv.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "scene/drainage_lines.hpp"
#include "core/log.hpp"
#include "scene/terrain_view.hpp"
#include "../cli/cli_support.hpp"
#include "drainage/dem_surface.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/stems.hpp"
#include "input/dem_reader.hpp"
#include "support/synthetic_terrain.hpp"
#include "surface/surface_mesh.hpp"
#include "surface/terrain_lod.hpp"

using namespace penink;
using namespace penink::test;
namespace fs = std::filesystem;

namespace {

// A temp dir holding a copy of volcano.asc (and its .prj), so the .dv cache lands there.
fs::path volcano_dir(const std::string& name) {
    const fs::path dir = fresh_dir("creases_" + name);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    if (fs::exists(PENINK_SOURCE_DIR "/examples/volcano.prj"))
        fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "volcano.prj");
    return dir;
}

// Removes a test's directory when the test passed (kept for inspection when it failed).
struct Cleanup {
    fs::path dir;
    ~Cleanup() {
        if (!::testing::Test::HasFailure()) fs::remove_all(dir);
    }
};

struct PathStats {
    std::size_t count = 0, points = 0;
    double length = 0.0;
    std::size_t wrong_kind = 0, outside = 0;
};

// The <g> of layer `id` (layers are not nested without --layers splits).
std::string layer_text(const std::string& svg, const std::string& id) {
    const std::size_t a = svg.find("inkscape:label=\"" + id + "\" id=\"" + id + "\"");
    if (a == std::string::npos) return "<missing>";
    return svg.substr(a, svg.find("</g>", a) - a);
}

PathStats path_stats(const std::string& layer, const std::string& kind, double width, double height) {
    PathStats s;
    static const std::regex path_re("<path d=\"([^\"]*)\"([^>]*)/>");
    static const std::regex num_re("-?[0-9]+(\\.[0-9]+)?");
    for (auto it = std::sregex_iterator(layer.begin(), layer.end(), path_re); it != std::sregex_iterator(); ++it) {
        ++s.count;
        if ((*it)[2].str().find("data-kind=\"" + kind + "\"") == std::string::npos) ++s.wrong_kind;
        const std::string d = (*it)[1].str();
        std::vector<double> v;
        for (auto n = std::sregex_iterator(d.begin(), d.end(), num_re); n != std::sregex_iterator(); ++n)
            v.push_back(std::stod(n->str()));
        for (std::size_t k = 0; k + 1 < v.size(); k += 2) {
            ++s.points;
            if (v[k] < -0.01 || v[k] > width + 0.01 || v[k + 1] < -0.01 || v[k + 1] > height + 0.01) ++s.outside;
            if (k >= 2) s.length += std::hypot(v[k] - v[k - 2], v[k + 1] - v[k - 1]);
        }
    }
    return s;
}

std::string scene_with_creases(const std::string& creases_keys) {
    return "[terrain]\ndem = \"volcano.asc\"\n[camera]\nwidth = 300\nheight = 225\n[creases]\n" + creases_keys + "\n";
}

}  // namespace

TEST(CreasesRender, DefaultRenderDrawsCreasesAndRidgesAndCachesDrainage) {
    const fs::path dir = volcano_dir("default");
    const Cleanup cleanup{dir};
    const RunResult r = run_penink("render volcano.asc --width 300 --height 225 -o x.svg --verbose", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("rebuilding"), std::string::npos) << r.output;  // no cache yet
    EXPECT_NE(r.output.find("drainage: wrote volcano.asc.dv"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("terrain: volcano.asc.lod: no terrain cache; building"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("terrain: wrote volcano.asc.lod"), std::string::npos) << r.output;
    ASSERT_TRUE(fs::exists(dir / "volcano.asc.dv"));
    ASSERT_TRUE(fs::exists(dir / "volcano.asc.lod"));
    const std::string svg = read_text(dir / "x.svg");
    const PathStats creases = path_stats(layer_text(svg, "creases"), "crease", 300, 225);
    const PathStats ridges = path_stats(layer_text(svg, "ridges"), "ridge", 300, 225);
    RecordProperty("crease_paths", int(creases.count));
    RecordProperty("crease_length_px", int(creases.length));
    RecordProperty("ridge_paths", int(ridges.count));
    RecordProperty("ridge_length_px", int(ridges.length));
    EXPECT_GT(creases.count, 5u);
    EXPECT_GT(ridges.count, 0u);
    EXPECT_GT(creases.length, 200.0);
    EXPECT_EQ(creases.wrong_kind, 0u);
    EXPECT_EQ(ridges.wrong_kind, 0u);
    EXPECT_EQ(creases.outside, 0u);
    EXPECT_EQ(ridges.outside, 0u);
    // Layer order of conventions.md: surface, ridges, creases, ..., silhouettes.
    const std::size_t ps = svg.find("id=\"surface\""), pr = svg.find("id=\"ridges\""), pc = svg.find("id=\"creases\""),
                      pl = svg.find("id=\"silhouettes\"");
    EXPECT_LT(ps, pr);
    EXPECT_LT(pr, pc);
    EXPECT_LT(pc, pl);
    ASSERT_NE(pl, std::string::npos);

    // Second render: the cache is read, and the drawing is byte-identical.
    const auto mtime = fs::last_write_time(dir / "volcano.asc.dv");
    const RunResult again = run_penink("render volcano.asc --width 300 --height 225 -o y.svg --verbose", dir);
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_NE(again.output.find("drainage: using cached volcano.asc.dv"), std::string::npos) << again.output;
    EXPECT_NE(again.output.find("terrain: using cached volcano.asc.lod"), std::string::npos) << again.output;
    EXPECT_EQ(again.output.find("rebuilding"), std::string::npos) << again.output;
    EXPECT_EQ(again.output.find("building"), std::string::npos) << again.output;
    EXPECT_EQ(fs::last_write_time(dir / "volcano.asc.dv"), mtime);
    EXPECT_EQ(read_text(dir / "y.svg"), svg);  // the mapped terrain draws what the one read did
}

// Both caches are keyed by the DEM alone: exaggeration 1, then 3, then 1 again read them and
// never rewrite them, and the two drawings at 1 are byte-identical.
TEST(CreasesRender, CachesSurviveAnExaggerationChange) {
    const fs::path dir = volcano_dir("exaggeration");
    const Cleanup cleanup{dir};
    const std::string cmd = "render volcano.asc --width 300 --height 225 --verbose";
    ASSERT_EQ(run_penink(cmd + " -o a.svg", dir).code, 0);
    const auto dv = fs::last_write_time(dir / "volcano.asc.dv"), lod = fs::last_write_time(dir / "volcano.asc.lod");
    for (const std::string& run : {cmd + " --vertical-exaggeration 3 -o b.svg", cmd + " -o c.svg"}) {
        const RunResult r = run_penink(run, dir);
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("drainage: using cached volcano.asc.dv"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("terrain: using cached volcano.asc.lod"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("building drainage database"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("wrote"), std::string::npos) << r.output;  // neither cache rewritten
    }
    EXPECT_EQ(fs::last_write_time(dir / "volcano.asc.dv"), dv);
    EXPECT_EQ(fs::last_write_time(dir / "volcano.asc.lod"), lod);
    EXPECT_EQ(read_text(dir / "c.svg"), read_text(dir / "a.svg"));
    EXPECT_NE(read_text(dir / "b.svg"), read_text(dir / "a.svg"));
}

TEST(CreasesRender, HighMinScoreRemovesAllCreases) {
    const fs::path dir = volcano_dir("minscore");
    const Cleanup cleanup{dir};
    write_text(dir / "scene.toml", scene_with_creases("min_score = 0.35"));
    RunResult r = run_penink("render scene.toml -o some.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const PathStats some = path_stats(layer_text(read_text(dir / "some.svg"), "creases"), "crease", 300, 225);
    // rs <= (2 + 0.5 + 4) / 3 - 2.5 < 0 everywhere with the default weights.
    write_text(dir / "scene.toml", scene_with_creases("min_score = 2.5"));
    r = run_penink("render scene.toml -o none.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string none = read_text(dir / "none.svg");
    EXPECT_GT(some.count, 0u);
    EXPECT_EQ(path_stats(layer_text(none, "creases"), "crease", 300, 225).count, 0u);
    EXPECT_GT(path_stats(layer_text(none, "ridges"), "ridge", 300, 225).count, 0u);  // [ridges] untouched
}

namespace {

struct Frame {  // volcano at 300x225 from the default viewpoint, drainage built in memory
    Scene scene;
    Terrain dem, view;
    Camera camera;
    SurfaceMesh mesh;
    DrainageDb db;
    Frame() {
        scene.source.dem = PENINK_SOURCE_DIR "/examples/volcano.asc";
        scene.view.camera.width = 300, scene.view.camera.height = 225;
        dem = read_dem(scene.source.dem);
        camera = scene_camera(scene, dem);
        view = terrain_for_view(dem, camera, scene, Log{});
        mesh = mesh_from_terrain(view);
        db = build_drainage_db(dem, DrainageOptions{});
    }
};

// A Frame rendered once (toward/away surface and depth) with its drainage lines uploaded; draws
// the creases and ridges of any variant of its scene.
struct RenderedFrame : Frame {
    TerrainRenderer renderer{test_context().gl(), mesh, camera.width, camera.height};
    FrameImages img = renderer.render(camera, {});
    DrainageLines lines{test_context().gl(), db, view};
    float D = max_visible_distance(img.toward);

    Drawing draw(const Scene& s) {
        Drawing d;
        PassTimings t;
        lines.draw(camera, s, renderer.surface_pass().toward_texture(), D, d, t);
        return d;
    }
};

struct LayerStats {
    std::size_t strokes = 0, points = 0, outside = 0;
    double length = 0.0;
    std::set<std::tuple<int, int, int, int>> segments;  // rounded to 1/100 px
};

LayerStats layer_stats(const Layer& layer, const std::string& kind, const Camera& cam) {
    LayerStats s;
    for (const Stroke& st : layer.strokes) {
        ++s.strokes;
        EXPECT_EQ(st.kind, kind);
        EXPECT_GE(st.strength, 0.0f);
        EXPECT_EQ(st.depth.size(), st.points.size());
        for (std::size_t i = 0; i < st.points.size(); ++i) {
            const glm::vec2 p = st.points[i];
            ++s.points;
            s.outside += p.x < 0 || p.y < 0 || p.x > cam.width || p.y > cam.height;
            if (i == 0) continue;
            const glm::vec2 q = st.points[i - 1];
            s.length += glm::length(p - q);
            s.segments.insert({int(std::lround(q.x * 100)), int(std::lround(q.y * 100)), int(std::lround(p.x * 100)),
                               int(std::lround(p.y * 100))});
        }
    }
    return s;
}

}  // namespace

TEST(CreasesRender, RaisingMinScoreRemovesCreasesInProcess) {
    RenderedFrame f;
    std::size_t stem_vertices = 0;
    for (const auto& stem : drainage_stems(f.db)) stem_vertices += stem.size();
    EXPECT_EQ(f.lines.crease_vertices(), stem_vertices);
    for (double spacing : {0.0, 4.0}) {  // without and with even-spacing thinning
        LayerStats previous;
        previous.length = 1e300, previous.points = SIZE_MAX, previous.strokes = SIZE_MAX;
        std::vector<std::size_t> strokes;
        for (double min_score : {-0.2, 0.0, 0.1, 0.2, 0.35, 0.5, 0.8, 1.2, 2.5}) {
            Scene s = f.scene;
            s.lines.creases.min_score = min_score, s.lines.creases.spacing_px = spacing;
            // No distance attenuation: drawing far stems whole or not at all
            // (whole_or_nothing_by_distance) is not monotone in min_score by design.
            s.lines.creases.distance_attenuation = 0.0;
            const Drawing d = f.draw(s);
            const LayerStats now = layer_stats(d.layer(LayerKind::creases), "crease", f.camera);
            EXPECT_EQ(now.outside, 0u);
            EXPECT_LE(now.length, previous.length + 1e-3) << "spacing " << spacing << " min_score " << min_score;
            EXPECT_LE(now.points, previous.points) << "spacing " << spacing << " min_score " << min_score;
            // Not a theorem (a run can split in two), but holds on volcano at every step.
            EXPECT_LE(now.strokes, previous.strokes) << "spacing " << spacing << " min_score " << min_score;
            if (spacing == 0.0 && previous.points != SIZE_MAX) {  // scores only shift: segments are a subset
                for (const auto& seg : now.segments) EXPECT_TRUE(previous.segments.count(seg)) << min_score;
            }
            RecordProperty("spacing" + std::to_string(int(spacing)) + "_min" + std::to_string(int(min_score * 100)) +
                               "_strokes_length",
                           std::to_string(now.strokes) + " " + std::to_string(int(now.length)));
            strokes.push_back(now.strokes);
            previous = now;
        }
        EXPECT_GT(strokes[1], strokes[5]);
        EXPECT_EQ(strokes.back(), 0u);
    }
}

TEST(CreasesRender, RidgesAndCreasesSwitchIndependently) {
    RenderedFrame f;
    Scene s = f.scene;
    const Drawing both = f.draw(s);
    s.lines.ridges.enabled = false;
    const Drawing no_ridges = f.draw(s);
    s.lines.ridges.enabled = true, s.lines.creases.enabled = false;
    const Drawing no_creases = f.draw(s);
    const LayerStats c = layer_stats(both.layer(LayerKind::creases), "crease", f.camera);
    const LayerStats r = layer_stats(both.layer(LayerKind::ridges), "ridge", f.camera);
    EXPECT_GT(c.strokes, 5u);
    EXPECT_GT(r.strokes, 0u);
    EXPECT_EQ(r.outside, 0u);
    EXPECT_TRUE(no_ridges.layer(LayerKind::ridges).strokes.empty());
    EXPECT_EQ(layer_stats(no_ridges.layer(LayerKind::creases), "crease", f.camera).segments, c.segments);
    EXPECT_TRUE(no_creases.layer(LayerKind::creases).strokes.empty());
    EXPECT_EQ(layer_stats(no_creases.layer(LayerKind::ridges), "ridge", f.camera).segments, r.segments);
    // D: the largest finite eye distance of the frame.
    float far = 0.0f;
    for (float v : f.img.toward.depth)
        if (std::isfinite(v)) far = std::max(far, v);
    EXPECT_EQ(f.D, far);
    EXPECT_GT(f.D, 0.0f);
}

namespace {

// Branch from `from` in `steps` 10 m steps of `dir` (order, downstream as given).
void add_branch(DrainageDb& db, glm::vec2 from, glm::vec2 dir, int steps, std::uint8_t order, std::int32_t down) {
    DvBranch b{};
    b.first = std::uint32_t(db.vertices.size()), b.count = std::uint32_t(steps + 1);
    b.order = order, b.downstream = down, b.basin = 1;
    for (int k = 0; k <= steps; ++k) {
        const glm::vec2 p = from + dir * (10.0f * k);
        db.vertices.push_back({p.x, p.y, 0.0f, 0.1f * float(k + 1)});
    }
    db.branches.push_back(b);
}

}  // namespace

TEST(CreasesRender, TributaryStaysJoinedToSmoothedMainStem) {
    // Flat ground; A (order 2) comes from the west to J = (0, 0) and turns south as C; B (order 1)
    // comes from the north and ends at J. Smoothing rounds the main stem's corner at J.
    DrainageDb db;
    add_branch(db, {-50, 0}, {1, 0}, 5, 2, 2);   // A
    add_branch(db, {0, 50}, {0, -1}, 5, 1, 2);   // B
    add_branch(db, {0, 0}, {0, -1}, 5, 2, -1);   // C
    db.upstream = {0, 1};
    db.branches[2].up_first = 0, db.branches[2].up_count = 2;
    db.branches[0].up_first = db.branches[1].up_first = 0;
    const Terrain ground = terrain_from_function(21, 21, 10.0, [](double, double) { return 0.0; });
    const SurfaceMesh mesh = mesh_from_terrain(ground);
    db.creases = listed_lines(db.vertices, drainage_stems(db));  // as the build makes them
    smooth_and_drape(db.creases, DemSurface(ground));
    Camera cam;  // 200 m above the origin, straight down, 1 px per metre: (x, y) -> (200 + x, 200 - y)
    cam.eye = {0.0, 0.0, 200.0};
    cam.azimuth = 0.0, cam.altitude = -90.0, cam.fov = 90.0, cam.width = 400, cam.height = 400;
    cam.near_plane = 1.0, cam.far_plane = 1000.0;
    GlContext& ctx = test_context();
    TerrainRenderer renderer(ctx.gl(), mesh, cam.width, cam.height);
    const FrameImages img = renderer.render(cam, {});
    DrainageLines lines(ctx.gl(), db, ground);
    Scene s;
    s.lines.creases.min_score = -10.0, s.lines.creases.distance_attenuation = 0.0, s.lines.creases.spacing_px = 0.0;
    s.lines.ridges.enabled = false;
    Drawing d;
    PassTimings t;
    lines.draw(cam, s, renderer.surface_pass().toward_texture(), max_visible_distance(img.toward), d, t);
    const std::vector<Stroke>& st = d.layer(LayerKind::creases).strokes;
    ASSERT_EQ(st.size(), 2u);
    const Stroke& main = st[0].points.size() == 11 ? st[0] : st[1];
    const Stroke& trib = st[0].points.size() == 11 ? st[1] : st[0];
    ASSERT_EQ(main.points.size(), 11u);  // A + C, J once
    ASSERT_EQ(trib.points.size(), 6u);
    EXPECT_NEAR(main.points.front().x, 150.0f, 1e-3);  // sources and outlet stay put
    EXPECT_NEAR(main.points.back().y, 250.0f, 1e-3);
    EXPECT_NEAR(trib.points.front().y, 150.0f, 1e-3);
    // The corner moved inside the bend (towards south-west: +y down, -x) by metres...
    const glm::vec2 j = main.points[5];
    EXPECT_LT(j.x, 199.0f);
    EXPECT_GT(j.y, 201.0f);
    // ...and the tributary's end went with it.
    EXPECT_NEAR(trib.points.back().x, j.x, 1e-3);
    EXPECT_NEAR(trib.points.back().y, j.y, 1e-3);
}

TEST(CreasesRender, DisabledCreasesLeaveAnEmptyLayer) {
    const fs::path dir = volcano_dir("disabled");
    const Cleanup cleanup{dir};
    write_text(dir / "scene.toml", scene_with_creases("enabled = false"));
    const RunResult r = run_penink("render scene.toml -o out.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "out.svg");
    ASSERT_NE(layer_text(svg, "creases"), "<missing>");
    EXPECT_EQ(path_stats(layer_text(svg, "creases"), "crease", 300, 225).count, 0u);
    EXPECT_GT(path_stats(layer_text(svg, "ridges"), "ridge", 300, 225).count, 0u);
}

namespace {

// Writes the cache with `penink drainage` (automatic factor, as render uses), replaces it by
// `damage(good bytes)` and renders: returns the render's output; `good` gets the intact bytes.
RunResult render_with_damaged_cache(const fs::path& dir, std::string& good,
                                    const std::function<std::string(std::string)>& damage) {
    EXPECT_EQ(run_penink("drainage volcano.asc -q", dir).code, 0);
    good = read_text(dir / "volcano.asc.dv");
    EXPECT_GT(good.size(), 1000u);
    std::ofstream(dir / "volcano.asc.dv", std::ios::binary) << damage(good);
    return run_penink("render volcano.asc --width 300 --height 225 -o out.svg --verbose", dir);
}

}  // namespace

TEST(CreasesRender, CorruptCacheIsRebuilt) {
    const fs::path dir = volcano_dir("corrupt");
    const Cleanup cleanup{dir};
    std::string good;
    const RunResult r = render_with_damaged_cache(dir, good, [](std::string b) {
        std::uint64_t lines_at = 0;  // the part a render reads: the creases' and ridges' records and index
        std::memcpy(&lines_at, b.data() + 24, 8);
        const std::size_t at = std::size_t(lines_at) + 88 + 28 * 5 + 1;  // one bit of the sixth crease's record
        b[at] = char(b[at] ^ 0x40);
        return b;
    });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: drainage: volcano.asc.dv: drainage database checksum mismatch (file corrupt); "
                            "rebuilding\n"),
              std::string::npos) << r.output;
    EXPECT_EQ(read_text(dir / "volcano.asc.dv"), good);  // rebuilt, deterministically
    EXPECT_GT(path_stats(layer_text(read_text(dir / "out.svg"), "creases"), "crease", 300, 225).count, 0u);
}

TEST(CreasesRender, TruncatedCacheIsRebuilt) {
    const fs::path dir = volcano_dir("truncated");
    const Cleanup cleanup{dir};
    std::string good;
    const RunResult r = render_with_damaged_cache(dir, good, [](std::string b) { return b.substr(0, b.size() / 3); });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: drainage: volcano.asc.dv: truncated drainage database; rebuilding\n"),
              std::string::npos) << r.output;
    EXPECT_EQ(read_text(dir / "volcano.asc.dv"), good);
    EXPECT_GT(path_stats(layer_text(read_text(dir / "out.svg"), "creases"), "crease", 300, 225).count, 0u);
}

TEST(CreasesRender, StaleCacheIsRebuilt) {
    const fs::path dir = volcano_dir("stale");
    const Cleanup cleanup{dir};
    ASSERT_EQ(run_penink("drainage volcano.asc -q", dir).code, 0);
    const std::string before = read_text(dir / "volcano.asc.dv");
    // One elevation edited: the DEM's fingerprint changes.
    std::string dem = read_text(dir / "volcano.asc");
    const std::size_t last = dem.find_last_of("0123456789");
    dem[last] = dem[last] == '9' ? '8' : char(dem[last] + 1);
    std::ofstream(dir / "volcano.asc", std::ios::binary) << dem;
    const RunResult s = run_penink("render volcano.asc --width 300 --height 225 -o d.svg --verbose", dir);
    ASSERT_EQ(s.code, 0) << s.output;
    EXPECT_NE(s.output.find("penink: drainage: volcano.asc.dv: drainage database is stale (DEM changed); rebuilding"),
              std::string::npos) << s.output;
    EXPECT_NE(read_text(dir / "volcano.asc.dv"), before);
}

TEST(CreasesRender, DrainageSubcommandWritesRasters) {
    const fs::path dir = volcano_dir("drainage");
    const Cleanup cleanup{dir};
    const RunResult r = run_penink("drainage volcano.asc --resample 1 --rasters rasters", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("drainage: wrote volcano.asc.dv"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "volcano.asc.dv"));
    GDALAllRegister();
    for (const char* name : {"flow_direction", "accumulation", "basin", "stream_order"}) {
        const fs::path p = dir / "rasters" / (std::string(name) + ".tif");
        GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(p.string().c_str(), GA_ReadOnly));
        ASSERT_NE(ds, nullptr) << p;
        EXPECT_EQ(ds->GetRasterXSize(), 61) << name;
        EXPECT_EQ(ds->GetRasterYSize(), 87) << name;
        double gt[6];
        ASSERT_EQ(ds->GetGeoTransform(gt), CE_None) << name;
        EXPECT_DOUBLE_EQ(gt[1], 10.0) << name;
        EXPECT_DOUBLE_EQ(gt[5], -10.0) << name;
        EXPECT_NE(std::string(ds->GetProjectionRef()).find("Zealand"), std::string::npos) << name;
        GDALClose(ds);
    }
    // -q: nothing printed; a bad factor is one error line with exit code 2.
    const RunResult q = run_penink("drainage volcano.asc --resample 1 -q -o quiet.dv", dir);
    EXPECT_EQ(q.code, 0);
    EXPECT_EQ(q.output, "");
    EXPECT_EQ(read_text(dir / "quiet.dv"), read_text(dir / "volcano.asc.dv"));
}

namespace {

// The render path's cache calls on `dem` read at exaggeration `e`: the database and the log.
DrainageDb render_cache(const fs::path& dem, double e, std::vector<std::string>& log) {
    DemOptions o;
    o.vertical_exaggeration = e;
    return load_or_build_drainage(dem.string(), read_dem(dem.string(), o), DrainageOptions{},
                                  [&](const std::string& m) { log.push_back(m); });
}

}  // namespace

// The cache holds unexaggerated lines: built at 1, it serves 3 and 1 again without being
// rebuilt or rewritten, and the lines a frame gets at 3 are those at 1 with z times 3 and
// normals normalize(3 nx, 3 ny, nz); a build started at 3 writes the same file.
TEST(CreasesRender, CacheSurvivesAnExaggerationChange) {
    const fs::path dir = volcano_dir("exaggeration");
    const Cleanup cleanup{dir};
    const fs::path dem = dir / "volcano.asc", cache = dir / "volcano.asc.dv";
    std::vector<std::string> log;
    const DrainageDb at1 = render_cache(dem, 1.0, log);
    ASSERT_EQ(log.back(), "drainage: wrote " + cache_file_report(cache.string()));
    const auto mtime = fs::last_write_time(cache);
    const std::string bytes = read_text(cache);
    const DrainageDb at3 = render_cache(dem, 3.0, log);
    EXPECT_EQ(log.back(), "drainage: using cached " + cache_file_report(cache.string()));
    const DrainageDb again = render_cache(dem, 1.0, log);
    EXPECT_EQ(log.back(), "drainage: using cached " + cache_file_report(cache.string()));
    EXPECT_EQ(log.size(), 4u);  // missing + wrote, then two reads
    EXPECT_EQ(fs::last_write_time(cache), mtime);
    EXPECT_TRUE(at3 == at1);
    EXPECT_TRUE(again == at1);

    DemOptions three;
    three.vertical_exaggeration = 3.0;
    const DrainageLineData l1 = prepare_drainage_lines(at1, read_dem(dem.string()));
    const DrainageLineData l3 = prepare_drainage_lines(at3, read_dem(dem.string(), three));
    for (const auto& [a, b] : {std::pair(&l1.creases, &l3.creases), std::pair(&l1.ridges, &l3.ridges)}) {
        ASSERT_EQ(a->positions.size(), b->positions.size());
        ASSERT_GT(a->positions.size(), 1000u);
        EXPECT_EQ(a->runs.size(), b->runs.size());
        std::size_t drawn = 0;
        for (std::size_t i = 0; i < a->positions.size(); ++i) {
            EXPECT_EQ(b->positions[i].x, a->positions[i].x);
            EXPECT_EQ(b->positions[i].y, a->positions[i].y);
            EXPECT_EQ(b->positions[i].z, float(3.0 * double(a->positions[i].z)));
            const glm::vec3 n = a->normals[i];
            if (n == glm::vec3(0.0f)) {
                EXPECT_EQ(b->normals[i], glm::vec3(0.0f));
                continue;
            }
            ++drawn;
            const glm::vec3 want = glm::normalize(glm::vec3(3.0f * n.x, 3.0f * n.y, n.z));
            EXPECT_LT(glm::length(b->normals[i] - want), 1e-6f) << i;
            EXPECT_EQ(b->flow[i], a->flow[i]);
        }
        EXPECT_GT(drawn, a->positions.size() / 2);
    }

    // a cache first built at exaggeration 3 (the DEM read again unexaggerated) is the same file
    const fs::path other = volcano_dir("exaggeration3");
    const Cleanup cleanup_other{other};
    fs::last_write_time(other / "volcano.asc", fs::last_write_time(dem));
    std::vector<std::string> log3;
    render_cache(other / "volcano.asc", 3.0, log3);
    ASSERT_EQ(log3.back(), "drainage: wrote " + cache_file_report((other / "volcano.asc.dv").string()));
    EXPECT_TRUE(read_text(other / "volcano.asc.dv") == bytes);
}

// `penink drainage DEM` writes the very cache a render then reads: neither the render path's
// call nor the binary at another exaggeration rebuilds or rewrites it.
TEST(CreasesRender, DrainageCommandWritesTheRendersCache) {
    const fs::path dir = volcano_dir("command_cache");
    const Cleanup cleanup{dir};
    ASSERT_EQ(run_penink("drainage volcano.asc -q", dir).code, 0);
    const fs::path cache = dir / "volcano.asc.dv";
    ASSERT_TRUE(fs::exists(cache));
    const auto mtime = fs::last_write_time(cache);
    std::vector<std::string> log;
    render_cache(dir / "volcano.asc", 1.0, log);
    ASSERT_EQ(log.size(), 1u);
    EXPECT_EQ(log[0], "drainage: using cached " + cache_file_report(cache.string()));
    const RunResult r = run_penink("render volcano.asc --width 300 --height 225 -o x.svg --verbose "
                                   "--vertical-exaggeration 2", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("drainage: using cached volcano.asc.dv"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("rebuilding"), std::string::npos) << r.output;
    EXPECT_EQ(fs::last_write_time(cache), mtime);
    EXPECT_GT(path_stats(layer_text(read_text(dir / "x.svg"), "creases"), "crease", 300, 225).count, 0u);
}

// A frame modelling part of the DEM gets exactly the stored lines whose box meets its box, cut
// as lines_in_box cuts them: the runs inside with one vertex beyond at each cut, those beyond
// never drawn (zero normal).
TEST(CreasesRender, CroppedModelGetsTheLinesMeetingItsBox) {
    const Terrain dem = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    const DrainageDb db = build_drainage_db(dem, DrainageOptions{});
    const Terrain model = crop_terrain(dem, GridWindow{10, 20, 45, 60});
    glm::dvec3 lo, hi;
    ASSERT_TRUE(terrain_bounds(model, lo, hi));
    const DrainageLineData data = prepare_drainage_lines(db, model);
    for (const auto& [set, got] : {std::pair(&db.creases, &data.creases), std::pair(&db.ridges, &data.ridges)}) {
        // every stored line cut to the box, in line order: what the frame must hold
        DvVertices flat;
        std::vector<std::vector<std::uint32_t>> lines;
        for (const DrapedVertex& v : set->vertices) flat.push_back({v.x, v.y, v.z, v.flow});
        for (const DrapedLine& l : set->lines) {
            lines.emplace_back();
            for (std::uint32_t k = 0; k < l.count; ++k) lines.back().push_back(l.first + k);
        }
        const auto pieces = lines_in_box(lines, flat, glm::vec2(lo), glm::vec2(hi));
        ASSERT_EQ(got->runs.size(), pieces.size());
        EXPECT_GT(pieces.size(), 10u);
        std::size_t i = 0, beyond = 0;
        for (std::size_t p = 0; p < pieces.size(); ++p) {
            EXPECT_EQ(got->runs[p].first, i);
            ASSERT_EQ(got->runs[p].count, pieces[p].size());
            for (std::uint32_t k : pieces[p]) {
                const DrapedVertex& v = set->vertices[k];
                EXPECT_EQ(got->positions[i], glm::vec3(v.x, v.y, v.z));
                const bool inside = v.x >= float(lo.x) && v.x <= float(hi.x) && v.y >= float(lo.y) && v.y <= float(hi.y);
                EXPECT_EQ(got->normals[i], inside ? glm::vec3(v.nx, v.ny, v.nz) : glm::vec3(0.0f));
                beyond += !inside;
                ++i;
            }
        }
        EXPECT_EQ(i, got->positions.size());
        EXPECT_GT(beyond, 0u);
        EXPECT_LT(got->positions.size(), set->vertices.size() / 2);
    }
}

namespace {

void expect_same_lines(const ScoredLineSet& a, const ScoredLineSet& b, const std::string& what) {
    ASSERT_EQ(a.positions.size(), b.positions.size()) << what;
    ASSERT_EQ(a.runs.size(), b.runs.size()) << what;
    for (std::size_t i = 0; i < a.runs.size(); ++i) {
        EXPECT_EQ(a.runs[i].first, b.runs[i].first) << what;
        EXPECT_EQ(a.runs[i].count, b.runs[i].count) << what;
    }
    EXPECT_TRUE(a.positions == b.positions) << what;
    EXPECT_TRUE(a.normals == b.normals) << what;
    EXPECT_TRUE(a.flow == b.flow) << what;
}

}  // namespace

// The render path's selection from the cache file (line records and index read and checked, the
// selected lines' vertices read from the file a batch at a time) gives exactly what the
// selection from the whole lines part in memory gives: same pieces, order and floats, for whole
// and cropped models, with and without screen-size culling, at exaggeration 1 and 2.
TEST(CreasesRender, StreamedSelectionEqualsTheInMemoryOne) {
    const fs::path dir = fs::temp_directory_path() / "penink_streamed_selection";
    fs::create_directories(dir);
    const Cleanup cleanup{dir};
    for (const std::string name : {"volcano", "jacksboro"}) {
        const std::string dem_path =
            std::string(PENINK_SOURCE_DIR) + (name == "volcano" ? "/tests/data/" : "/examples/") + name + ".tif";
        const Terrain dem = read_dem(dem_path);
        const DrainageDb full = build_drainage_db(dem, DrainageOptions{});
        const std::string cache = (dir / (name + ".dv")).string();
        write_drainage_db(cache, full);
        const DrainageDb db = drainage_lines_only(full);
        DrainageLineSource source;
        source.db = read_drainage_line_index(cache, &db.fingerprint, source.vertices);
        ASSERT_TRUE(source.vertices.file);
        EXPECT_TRUE(source.db.creases.vertices.empty() && source.db.ridges.vertices.empty());
        EXPECT_TRUE(source.db.creases.lines == db.creases.lines && source.db.creases.index == db.creases.index);
        EXPECT_TRUE(source.db.ridges.lines == db.ridges.lines && source.db.ridges.index == db.ridges.index);
        for (const double e : {1.0, 2.0}) {
            DemOptions o;
            o.vertical_exaggeration = e;
            const Terrain at_e = read_dem(dem_path, o);
            Scene scene;
            scene.view.camera.width = 400, scene.view.camera.height = 300;
            const Camera cam = scene_camera(scene, at_e);
            const int c = at_e.cols, r = at_e.rows;
            const std::vector<Terrain> models = {at_e, crop_terrain(at_e, GridWindow{c / 4, r / 5, c / 2 + 3, r * 3 / 4}),
                                                 crop_terrain(at_e, GridWindow{0, r / 2, c / 3, r})};
            EXPECT_LT(prepare_drainage_lines(db, at_e, LineCulling{{cam}, 20.0f}).creases.positions.size(),
                      prepare_drainage_lines(db, at_e).creases.positions.size());
            for (std::size_t m = 0; m < models.size(); ++m)
                for (const LineCulling& culling : {LineCulling{}, LineCulling{{cam}, 2.0f}, LineCulling{{cam}, 20.0f}}) {
                    const DrainageLineData want = prepare_drainage_lines(db, models[m], culling);
                    const std::string what = name + " e " + std::to_string(e) + " model " + std::to_string(m) +
                                             " min_px " + std::to_string(culling.min_px);
                    if (culling.cameras.empty()) {
                        EXPECT_GT(want.creases.positions.size(), 100u) << what;
                    }
                    // the default batches, or many small ones (a read for each few lines)
                    source.batch_bytes = m == 1 ? std::size_t(64) << 10 : std::size_t(4) << 20;
                    const DrainageLineData got = prepare_drainage_lines(source, models[m], culling);
                    expect_same_lines(want.creases, got.creases, what + " creases");
                    expect_same_lines(want.ridges, got.ridges, what + " ridges");
                }
        }
    }
}

// Vertex decimation: with a camera, inside each written run's drawable part consecutive vertices
// lie at least decimate_px pixels apart on screen (measured with the same bound as the culling:
// distance times lod_pixel_scale over the eye distance), except next to the part's ends; without
// decimation every vertex of the same lines is written.
TEST(CreasesRender, DecimationKeepsVerticesHalfAPixelApart) {
    const std::string dem_path = PENINK_SOURCE_DIR "/examples/jacksboro.tif";
    const Terrain dem = read_dem(dem_path);
    const DrainageDb db = build_drainage_db(dem, DrainageOptions{});
    Scene scene;
    scene.view.camera.width = 400, scene.view.camera.height = 300;
    const Camera cam = scene_camera(scene, dem);
    const DrainageLineData all = prepare_drainage_lines(db, dem, LineCulling{{cam}, 0.0f, 0.0f});
    const DrainageLineData few = prepare_drainage_lines(db, dem, LineCulling{{cam}, 0.0f, 0.5f});
    ASSERT_EQ(all.creases.runs.size(), few.creases.runs.size());  // same pieces, fewer vertices
    EXPECT_LT(few.creases.positions.size() * 2, all.creases.positions.size());
    const double scale = lod_pixel_scale(cam);
    std::size_t checked = 0;
    for (const VertexRun& run : few.creases.runs) {
        ASSERT_GE(run.count, 2u);
        // run.first + 1 .. run.first + count - 3: neither next to a cut vertex nor an end
        for (std::uint32_t i = run.first + 2; i + 2 < run.first + run.count; ++i) {
            const glm::dvec3 p(few.creases.positions[i]), q(few.creases.positions[i - 1]);
            EXPECT_GE(glm::length(p - q) * scale / glm::length(p - cam.eye), 0.5 - 1e-6) << i;
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000u);
}

// The render path's cache read (load_or_build_drainage with `in_file`) checks what it reads, the
// line records and index: one bit flipped in a ridge's record is found and the cache rebuilt,
// after which the file is used with its vertices and the creases' source left in it. A bit
// flipped in the creases' source is found when a frame reads its page: the frame reads the cache
// whole, which rebuilds it, and draws what a sound cache draws.
TEST(CreasesRender, StreamedCacheReadRebuildsACorruptRecord) {
    const fs::path dir = volcano_dir("streamed_corrupt");
    const Cleanup cleanup{dir};
    ASSERT_EQ(run_penink("drainage volcano.asc -q", dir).code, 0);
    const fs::path dem = dir / "volcano.asc", cache = dir / "volcano.asc.dv";
    const std::string good = read_text(cache);
    DvLineVertices where;
    const DrainageDb stored = read_drainage_line_index(cache.string(), nullptr, where);
    ASSERT_EQ(where.count[0], 0u);  // the creases: built by the frames from their source
    ASSERT_GT(where.count[1], 100u);
    ASSERT_GT(stored.crease_source_size, 1000u);
    const std::size_t source_bytes = std::size_t(stored.crease_source_size);
    std::uint64_t lines_at = 0;
    std::memcpy(&lines_at, good.data() + 24, 8);
    // the lines part's header 72 B, the empty crease set 16 B of counts and its index, then the
    // ridges' counts (16 B) and records: where its index ends, measured as the part's size less
    // what follows the ridges' records
    const std::size_t source_at = good.size() - 16 - 8 * stored.crease_source_sums.size() - source_bytes;
    const std::size_t ridges_records_end =
        source_at - 8 - (28 * where.count[1] + 8 * ((where.count[1] + 1023) / 1024) + 16 +
                         8 * stored.ridges.index.level_cols.size() + 4 * stored.ridges.index.start.size() +
                         4 * stored.ridges.index.ids.size());
    ASSERT_GT(ridges_records_end, std::size_t(lines_at) + 88 + 28 * 8);
    {
        std::string bad = good;
        const std::size_t at = ridges_records_end - 28 * 7 + 5;
        bad[at] = char(bad[at] ^ 0x10);
        std::ofstream(cache, std::ios::binary) << bad;
        std::vector<std::string> log;
        DvLineVertices in_file;
        const DrainageDb built = load_or_build_drainage(dem.string(), read_dem(dem.string()), DrainageOptions{},
                                                        [&](const std::string& m) { log.push_back(m); }, {}, &in_file);
        ASSERT_EQ(log.size(), 2u);
        EXPECT_EQ(log[0], "penink: drainage: " + cache.string() +
                              ": drainage database checksum mismatch (file corrupt); rebuilding");
        EXPECT_FALSE(in_file.file);  // a build hands its lines directly
        EXPECT_FALSE(built.ridges.vertices.empty());
        ASSERT_EQ(built.crease_source.size(), source_bytes);
        EXPECT_EQ(std::memcmp(built.crease_source.data(), good.data() + source_at, source_bytes), 0);
        EXPECT_EQ(read_text(cache), good);
        const DrainageDb cached = load_or_build_drainage(dem.string(), read_dem(dem.string()), DrainageOptions{},
                                                         [&](const std::string& m) { log.push_back(m); }, {}, &in_file);
        EXPECT_EQ(log.back(), "drainage: using cached " + cache_file_report(cache.string()));
        ASSERT_TRUE(in_file.file);
        EXPECT_TRUE(cached.ridges.vertices.empty());
        EXPECT_TRUE(cached.crease_source.empty() && cached.crease_source_pages);
        EXPECT_TRUE(cached.ridges.lines == built.ridges.lines && cached.ridges.index == built.ridges.index);
        DrapedVertices v(built.ridges.vertices.size());
        in_file.read(1, 0, v.size(), v.data());
        EXPECT_TRUE(v == built.ridges.vertices);
    }
    ASSERT_EQ(run_penink("render volcano.asc --width 300 --height 225 -o sound.svg -q", dir).code, 0);
    fs::remove_all(dir / "volcano.asc.dv.tiles");  // the frame builds its creases: it reads every page
    std::string bad = good;
    bad[source_at + source_bytes / 2] = char(bad[source_at + source_bytes / 2] ^ 0x10);
    std::ofstream(cache, std::ios::binary) << bad;
    const RunResult r = run_penink("render volcano.asc --width 300 --height 225 -o damaged.svg --verbose", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("drainage: using cached volcano.asc.dv"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("damaged drainage cache; reading it whole"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("drainage database checksum mismatch (file corrupt); rebuilding"), std::string::npos)
        << r.output;
    EXPECT_EQ(read_text(dir / "damaged.svg"), read_text(dir / "sound.svg"));
    EXPECT_EQ(read_text(cache), good);
}

// The creases paper's Table 5 weights (slope .1, illumination .3, flow .6) with Figure 15's min
// scores .10, .19, .25: under "paper" (the weighted mean) each step draws less and .25 still draws;
// under "thirds" every score is at most (.1 + .3 + .6) / 3 = 1/3 and from .19 on a vertex needs a
// weighted sum of .57 (strong flow and deep shade), which volcano does not have: nothing is drawn.
// Table 5's own .8 asks a weighted mean of .8 + attenuation, out of reach on volcano under both
// (measured with examples/volcano_table5.toml: docs/reproduction.md).
TEST(CreasesRender, Table5WeightsDrawUnderPaperNormalisationOnly) {
    RenderedFrame f;
    const auto strokes = [&](ScoreNormalisation n, double min_score) {
        Scene s = f.scene;
        s.lines.creases.slope_weight = 0.1, s.lines.creases.illumination_weight = 0.3, s.lines.creases.flow_weight = 0.6;
        s.lines.creases.min_score = min_score, s.lines.creases.normalisation = n;
        const LayerStats st = layer_stats(f.draw(s).layer(LayerKind::creases), "crease", f.camera);
        RecordProperty(std::string(score_normalisation_name(n)) + "_min" + std::to_string(int(std::lround(min_score * 100))),
                       std::to_string(st.strokes) + " " + std::to_string(int(st.length)));
        return st;
    };
    const LayerStats p10 = strokes(ScoreNormalisation::paper, 0.10), p19 = strokes(ScoreNormalisation::paper, 0.19),
                     p25 = strokes(ScoreNormalisation::paper, 0.25), p80 = strokes(ScoreNormalisation::paper, 0.8);
    const LayerStats t10 = strokes(ScoreNormalisation::thirds, 0.10), t19 = strokes(ScoreNormalisation::thirds, 0.19),
                     t25 = strokes(ScoreNormalisation::thirds, 0.25), t80 = strokes(ScoreNormalisation::thirds, 0.8);
    EXPECT_GT(p10.length, p19.length);
    EXPECT_GE(p19.length, p25.length);
    EXPECT_GT(p25.strokes, 0u);
    EXPECT_GT(p10.length, t10.length);  // the same weights score 3x higher under "paper"
    EXPECT_EQ(t19.strokes, 0u);
    EXPECT_EQ(t25.strokes, 0u);
    EXPECT_EQ(t80.strokes, 0u);
    EXPECT_EQ(p80.strokes, 0u);
}

// The rank reading (each term its percentile among the visible vertices, lines/crease_scores.hpp):
// Table 5's .8 then keeps the vertices whose weighted mean percentile passes .8 plus the
// attenuation, the top few per cent (on volcano 3 % of the visible vertices: docs/reproduction.md),
// so it draws, and less than Figure 15's thresholds, which draw less at each step.
TEST(CreasesRender, Table5MinScoreDrawsTheTopOfTheNetworkUnderRankNormalisation) {
    RenderedFrame f;
    const auto strokes = [&](double min_score) {
        Scene s = f.scene;
        s.lines.creases.slope_weight = 0.1, s.lines.creases.illumination_weight = 0.3, s.lines.creases.flow_weight = 0.6;
        s.lines.creases.min_score = min_score, s.lines.creases.normalisation = ScoreNormalisation::rank;
        const LayerStats st = layer_stats(f.draw(s).layer(LayerKind::creases), "crease", f.camera);
        RecordProperty("rank_min" + std::to_string(int(std::lround(min_score * 100))),
                       std::to_string(st.strokes) + " " + std::to_string(int(st.length)));
        return st;
    };
    const LayerStats r10 = strokes(0.10), r25 = strokes(0.25), r60 = strokes(0.6), r80 = strokes(0.8),
                     r99 = strokes(0.99);
    EXPECT_GE(r10.length, r25.length);
    EXPECT_GT(r25.length, r60.length);
    EXPECT_GT(r60.length, r80.length);
    EXPECT_GT(r80.strokes, 0u);
    EXPECT_EQ(r99.strokes, 0u);  // a mean percentile of .99 plus the attenuation: out of reach
}
