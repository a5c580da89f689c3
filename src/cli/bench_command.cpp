#include "cli/bench_command.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/progress_bar.hpp"
#include "cli/scene_drawing.hpp"
#include "cli/terrain_drawing.hpp"
#include "cli/terrain_view.hpp"
#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "lines/line_accuracy.hpp"
#include "lines/object_silhouettes.hpp"
#include "surface/pn_tessellation.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double f1(double p, double r) { return p + r > 0 ? 2 * p * r / (p + r) : 0.0; }

SilhouetteMethod parse_method(const std::string& m) {
    if (m == "toward-away") return SilhouetteMethod::toward_away;
    if (m == "adjacency") return SilhouetteMethod::adjacency;
    if (m == "object-space") return SilhouetteMethod::object_space;
    throw Error("cli", "", "--methods: unknown method \"" + m + "\" (use toward-away, adjacency, object-space)");
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string f; std::getline(s, f, ',');) out.push_back(f);
    return out;
}

}  // namespace

std::vector<int> parse_int_list(const std::string& text, const std::string& option) {
    std::vector<int> out;
    for (const std::string& f : split(text)) {
        std::size_t used = 0;
        int v = 0;
        try {
            v = std::stoi(f, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != f.size() || f.empty() || v < 1 || v > 64)
            throw Error("cli", "", option + ": \"" + f + "\" is not a level between 1 and 64");
        out.push_back(v);
    }
    if (out.empty()) throw Error("cli", "", option + ": empty list");
    return out;
}

std::vector<std::pair<int, int>> parse_sizes(const std::string& text) {
    std::vector<std::pair<int, int>> out;
    for (const std::string& f : split(text)) {
        int w = 0, h = 0;
        char x = 0, extra = 0;
        std::istringstream s(f);
        if (!(s >> w >> x >> h) || x != 'x' || (s >> extra) || w < 8 || h < 8 || w > 8192 || h > 8192)
            throw Error("cli", "", "--sizes: \"" + f + "\" is not WIDTHxHEIGHT (8..8192 pixels)");
        out.emplace_back(w, h);
    }
    if (out.empty()) throw Error("cli", "", "--sizes: empty list");
    return out;
}

std::string bench_csv(const std::vector<BenchRow>& rows) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    s << "group,view,width,height,method,max_level,adaptive,culling,cropping,cells,ms_per_frame,tft_ms,aft_ms,sil_ms,"
         "precision_1px,recall_1px,precision_2px,recall_2px,mean_drawn_to_ref_px,mean_ref_to_drawn_px,reference_ms\n";
    for (const BenchRow& r : rows)
        s << r.group << "," << r.view << "," << r.width << "," << r.height << "," << r.method << "," << r.level << ","
          << r.adaptive << "," << r.culling << "," << r.cropping << "," << r.cells << "," << r.ms << "," << r.tft
          << "," << r.aft << "," << r.sil << "," << r.p1 << "," << r.r1 << "," << r.p2 << "," << r.r2 << ","
          << r.drawn_to_ref << "," << r.ref_to_drawn << "," << r.ref_ms << "\n";
    return s.str();
}

std::string bench_table(const std::vector<BenchRow>& rows) {
    std::ostringstream s;
    s << std::fixed;
    s << "group  view   size       method        L  adapt cull crop  cells    ms/frame    TFT     SIL    P@1   R@1   "
         "P@2   R@2   d->r  r->d\n";
    for (const BenchRow& r : rows) {
        std::ostringstream size;
        size << r.width << "x" << r.height;
        s << std::left << std::setw(7) << r.group << std::setw(7) << r.view << std::setw(11) << size.str()
          << std::setw(14) << r.method << std::right << std::setw(2) << r.level << "  " << std::setw(5)
          << (r.adaptive ? "on" : "off") << std::setw(5) << (r.culling ? "on" : "off") << std::setw(5)
          << (r.cropping ? "on" : "off") << std::setw(7) << r.cells << std::setprecision(1) << std::setw(12) << r.ms
          << std::setw(8) << r.tft << std::setw(8) << r.sil << std::setprecision(3) << std::setw(7) << r.p1
          << std::setw(6) << r.r1 << std::setw(6) << r.p2 << std::setw(6) << r.r2 << std::setprecision(2)
          << std::setw(6) << r.drawn_to_ref << std::setw(6) << r.ref_to_drawn << "\n";
    }
    return s.str();
}

std::vector<ChartSeries> bench_chart_series(const std::vector<BenchRow>& rows) {
    const std::map<std::string, std::string> colours = {
        {"toward-away", "#1f77b4"}, {"adjacency", "#d62728"}, {"object-space", "#2ca02c"}};
    const std::vector<std::string> dashes = {"", "8,4", "2,3", "12,3,3,3"};
    std::vector<ChartSeries> series;
    std::vector<std::string> sizes;
    for (const BenchRow& r : rows) {
        if (r.group != "sweep") continue;
        const std::string size = std::to_string(r.width) + "x" + std::to_string(r.height);
        auto si = std::find(sizes.begin(), sizes.end(), size);
        if (si == sizes.end()) sizes.push_back(size), si = sizes.end() - 1;
        const std::string name = r.method + " " + size;
        auto it = std::find_if(series.begin(), series.end(), [&](const ChartSeries& c) { return c.name == name; });
        if (it == series.end()) {
            const auto c = colours.find(r.method);
            series.push_back({name, c == colours.end() ? "#000000" : c->second,
                              dashes[std::size_t(si - sizes.begin()) % dashes.size()], {}});
            it = series.end() - 1;
        }
        it->points.push_back({r.ms, f1(r.p1, r.r1), "L" + std::to_string(r.level)});
    }
    return series;
}

namespace {

// One camera over one modelled terrain, with its exact reference silhouettes.
struct BenchView {
    std::string name;
    Camera camera;
    SurfaceMesh mesh;
    std::size_t cells = 0;
    std::vector<ImagePolyline> reference;
    double ref_ms = 0;
};

std::unique_ptr<BenchView> make_view(const Scene& scene, const Terrain& dem, int w, int h, bool zoom, bool crop,
                                     const Log& log) {
    auto v = std::make_unique<BenchView>();
    Scene sized = scene;
    sized.camera.width = w, sized.camera.height = h;
    v->name = zoom ? "zoom4" : "scene";
    v->camera = scene_camera(sized, dem);
    if (zoom) v->camera.fov /= 4.0;
    Terrain t = dem;
    if (crop) {
        t = terrain_for_view(dem, v->camera, sized, log);
    } else {
        glm::dvec3 lo, hi;
        terrain_bounds(dem, lo, hi);
        fit_depth_range(v->camera, lo, hi);
    }
    v->cells = std::size_t(t.cols - 1) * (t.rows - 1);
    v->mesh = mesh_from_terrain(t);
    return v;
}

// Exact references: object-space silhouettes of the PN surface finely tessellated on the CPU
// (edges ref_edge_px long on screen, max level 16), all visible runs. Computed once per camera
// pose at the largest image size asked for; a smaller image of the same pose and aspect gets the
// same lines scaled (pixel coordinates scale with the image; the visibility does not change).
struct ReferenceCache {
    struct Entry {
        Camera camera;
        std::vector<ImagePolyline> lines;
        double ms = 0;
    };
    double edge_px = 2.0;
    std::vector<Entry> entries;

    static bool same_pose(const Camera& a, const Camera& b) {
        return a.eye == b.eye && a.azimuth == b.azimuth && a.altitude == b.altitude && a.fov == b.fov &&
               double(a.width) * b.height == double(a.height) * b.width;
    }
    void compute(const BenchView& v) {
        const auto t0 = Clock::now();
        const glm::vec2 viewport(float(v.camera.width), float(v.camera.height));
        const PnTessellation t = tessellate_pn_surface(v.mesh, view_projection(v.camera), viewport, float(edge_px), 16);
        entries.push_back({v.camera, silhouette_polylines(object_space_silhouettes(t.pos, t.tri, v.camera), false), 0});
        entries.back().ms = ms_since(t0);
    }
    // Fills v.reference (and v.ref_ms) from a cached pose, computing it when new.
    void fill(BenchView& v) {
        auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) { return same_pose(e.camera, v.camera); });
        if (it == entries.end()) compute(v), it = entries.end() - 1;
        const float k = float(v.camera.width) / float(it->camera.width);
        v.reference = it->lines;
        for (ImagePolyline& line : v.reference)
            for (glm::vec2& p : line) p *= k;
        v.ref_ms = it->ms;
    }
};

// Median wall ms of k frames after warm-up (GPU pass times of that frame) and the accuracy of
// the last frame's silhouette mask against the view's reference.
void measure(TerrainRenderer& renderer, const BenchView& v, const FrameOptions& fo, int frames, int warmup,
             const std::vector<ImagePolyline>& reference, BenchRow& row) {
    for (int i = 0; i < warmup; ++i) renderer.render(v.camera, fo);
    std::vector<std::pair<double, PassTimings>> times;
    FrameImages last;
    for (int i = 0; i < std::max(1, frames); ++i) {
        const auto t0 = Clock::now();
        last = renderer.render(v.camera, fo);
        Drawing d;
        d.width = v.camera.width, d.height = v.camera.height;
        add_frame_lines(last, v.mesh, v.camera, d);
        times.emplace_back(ms_since(t0), last.times);
    }
    std::sort(times.begin(), times.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const auto& med = times[times.size() / 2];
    row.ms = med.first, row.tft = med.second.tft, row.aft = med.second.aft, row.sil = med.second.sil;
    const LineAccuracy a = line_accuracy(last.silhouettes, reference, {1.0, 2.0});
    row.p1 = a.at(1.0).precision, row.r1 = a.at(1.0).recall;
    row.p2 = a.at(2.0).precision, row.r2 = a.at(2.0).recall;
    row.drawn_to_ref = a.mean_drawn_to_reference, row.ref_to_drawn = a.mean_reference_to_drawn;
    row.view = v.name, row.cells = v.cells, row.ref_ms = v.ref_ms;
    row.width = v.camera.width, row.height = v.camera.height;
}

struct BenchRun {
    const BenchOptions& o;
    const Scene& scene;
    const Terrain& dem;
    GlContext& context;
    const Log& log;
    ReferenceCache references;
    std::vector<BenchRow> rows;
};

void sweep(BenchRun& run, const std::vector<int>& levels, const std::vector<std::pair<int, int>>& sizes,
           const std::vector<std::string>& methods) {
    ProgressBar bar(std::cerr, stderr_is_terminal(), "bench", int(sizes.size() * methods.size() * levels.size()));
    const auto largest = *std::max_element(sizes.begin(), sizes.end());
    run.references.compute(*make_view(run.scene, run.dem, largest.first, largest.second, false, true, run.log));
    for (const auto& [w, h] : sizes) {
        auto view = make_view(run.scene, run.dem, w, h, false, true, run.log);
        run.references.fill(*view);
        TerrainRenderer renderer(run.context.gl(), view->mesh, w, h);
        for (const std::string& m : methods) {
            for (std::size_t li = 0; li < levels.size(); ++li) {
                const int level = levels[li];
                FrameOptions fo;
                fo.silhouette_method = parse_method(m);
                fo.tessellation.max_level = level, fo.tessellation.target_edge_px = run.scene.tess_target_edge_px;
                BenchRow row;
                row.group = "sweep", row.method = m, row.level = level;
                const bool cpu = fo.silhouette_method == SilhouetteMethod::object_space;
                // One frame for the CPU method (no JIT); programs warm up once per renderer and method.
                measure(renderer, *view, fo, cpu ? 1 : run.o.frames, cpu || li > 0 ? 0 : run.o.warmup,
                        view->reference, row);
                run.rows.push_back(row);
                bar.step(m + " " + std::to_string(w) + "x" + std::to_string(h) + " L" + std::to_string(level), row.ms);
            }
        }
    }
    bar.finish();
}

// Each "model no more than a scene needs" feature off in turn, then all off, at the scene's size.
void needs_rows(BenchRun& run, int level, int w, int h) {
    struct Config { bool adaptive, culling, cropping; };
    const Config configs[] = {{true, true, true}, {false, true, true}, {true, false, true}, {true, true, false},
                              {false, false, false}};
    for (bool zoom : {false, true}) {
        auto cropped = make_view(run.scene, run.dem, w, h, zoom, true, run.log);
        auto whole = make_view(run.scene, run.dem, w, h, zoom, false, run.log);
        run.references.fill(*cropped);
        TerrainRenderer rc(run.context.gl(), cropped->mesh, w, h), rw(run.context.gl(), whole->mesh, w, h);
        bool warm_c = false, warm_w = false;  // warm up each renderer once
        for (const Config& c : configs) {
            bool& warm = c.cropping ? warm_c : warm_w;
            const int warmup = warm ? 0 : run.o.warmup;
            warm = true;
            FrameOptions fo;
            fo.tessellation.max_level = level;
            fo.tessellation.target_edge_px = c.adaptive ? run.scene.tess_target_edge_px : 1e-3f;  // fixed: all at max
            fo.tessellation.cull_patches = c.culling;
            BenchRow row;
            row.group = "needs", row.method = "toward-away", row.level = level;
            row.adaptive = c.adaptive, row.culling = c.culling, row.cropping = c.cropping;
            BenchView& v = c.cropping ? *cropped : *whole;
            measure(c.cropping ? rc : rw, v, fo, run.o.frames, warmup, cropped->reference, row);
            row.ref_ms = cropped->ref_ms;
            run.rows.push_back(row);
        }
    }
}

Scene bench_scene(const std::string& input) {
    Scene scene = load_scene(input);
    validate_scene(scene);
    if (is_mesh_scene(scene)) throw Error("bench", input, "bench measures terrains (a DEM or a scene with [terrain])");
    return scene;
}

}  // namespace

Subcommand add_bench_command(CLI::App& app) {
    auto options = std::make_shared<BenchOptions>();
    BenchOptions& o = *options;
    CLI::App* cmd = app.add_subcommand(
        "bench", "Speed against accuracy of the silhouette methods: DIR/bench.csv, DIR/speed_accuracy.svg");
    cmd->add_option("input", o.input, "DEM or terrain scene file (.toml)")->required();
    cmd->add_option("--out", o.out_dir, "Output directory (created when missing)")->required();
    cmd->add_option("--levels", o.levels, "Tessellation max_level values (default 1,2,4,8)");
    cmd->add_option("--sizes", o.sizes, "Image sizes WxH (default 500x375,1000x750,2000x1500)");
    cmd->add_option("--methods", o.methods, "Silhouette methods (default toward-away,adjacency,object-space)");
    cmd->add_option("--frames", o.frames, "Frames timed per configuration, median reported (default 3)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--warmup", o.warmup, "Untimed frames first (default 1)")->check(CLI::NonNegativeNumber);
    cmd->add_option("--ref-edge-px", o.ref_edge_px, "Reference tessellation: edges this long on screen at the largest size (default 3)")
        ->check(CLI::PositiveNumber);
    cmd->add_flag("!--no-needs", o.needs, "Leave out the culling / cropping / adaptive tessellation rows");
    cmd->add_option("--needs-size", o.needs_size, "Image size WxH of those rows (default: the scene's)");
    cmd->add_option("--gl", o.gl, "OpenGL backend: osmesa (software, default) or egl (GPU)")
        ->check(CLI::IsMember({"osmesa", "egl"}));
    cmd->add_flag("-v,--verbose", o.verbose, "Print modelled cells per view");
    return {cmd, [options] { return run_bench(*options); }};
}

int run_bench(const BenchOptions& o) {
    const Log log{o.verbose};
    const std::vector<int> levels = parse_int_list(o.levels, "--levels");
    const auto sizes = parse_sizes(o.sizes);
    const std::vector<std::string> methods = split(o.methods);
    for (const std::string& m : methods) parse_method(m);
    const Scene scene = bench_scene(o.input);
    const Terrain dem = read_scene_dem(scene);
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (!fs::is_directory(o.out_dir)) throw Error("bench", o.out_dir, "cannot create the output directory");
    const auto context = make_gl_context(parse_gl_backend(o.gl));
    BenchRun run{o, scene, dem, *context, log, {o.ref_edge_px, {}}, {}};
    sweep(run, levels, sizes, methods);
    if (o.needs) {
        const auto size = o.needs_size.empty() ? std::pair{scene.camera.width, scene.camera.height}
                                               : parse_sizes(o.needs_size).front();
        needs_rows(run, *std::max_element(levels.begin(), levels.end()), size.first, size.second);
    }
    write_file_atomically((fs::path(o.out_dir) / "bench.csv").string(), bench_csv(run.rows));
    ChartText text;
    text.title = "penink bench: " + fs::path(o.input).filename().string() + ", silhouettes against the exact reference";
    text.subtitle = context->description();
    text.y_label = "silhouette accuracy: F1 of precision and recall at 1 px";
    write_speed_accuracy_chart((fs::path(o.out_dir) / "speed_accuracy.svg").string(), bench_chart_series(run.rows), text);
    std::cout << bench_table(run.rows);
    return 0;
}

}  // namespace penink
