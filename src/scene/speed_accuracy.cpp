#include "scene/speed_accuracy.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "core/progress_bar.hpp"
#include "core/stopwatch.hpp"
#include "lines/line_accuracy.hpp"
#include "scene/raycast_reference.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

namespace {

double f1(double p, double r) { return p + r > 0 ? 2 * p * r / (p + r) : 0.0; }

}  // namespace

std::string bench_csv(const std::vector<BenchRow>& rows) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    s << "group,view,width,height,method,max_level,tolerance_px,adaptive,culling,cropping,cells,ms_per_frame,tft_ms,aft_ms,sil_ms,"
         "precision_1px,recall_1px,precision_2px,recall_2px,mean_drawn_to_ref_px,mean_ref_to_drawn_px,reference_ms,"
         "ms_min,ms_max,reference\n";
    for (const BenchRow& r : rows)
        s << r.group << "," << r.view << "," << r.width << "," << r.height << "," << r.method << "," << r.level << ","
          << r.tolerance_px << "," << r.adaptive << "," << r.culling << "," << r.cropping << "," << r.cells << "," << r.ms << "," << r.tft
          << "," << r.aft << "," << r.sil << "," << r.p1 << "," << r.r1 << "," << r.p2 << "," << r.r2 << ","
          << r.drawn_to_ref << "," << r.ref_to_drawn << "," << r.ref_ms << "," << r.ms_min << "," << r.ms_max << ","
          << r.reference << "\n";
    return s.str();
}

std::string bench_table(const std::vector<BenchRow>& rows) {
    std::ostringstream s;
    s << std::fixed;
    s << "group  view   size       method        L   tol  adapt cull crop     cells    ms/frame    TFT     SIL    P@1   R@1   "
         "P@2   R@2   d->r  r->d\n";
    for (const BenchRow& r : rows) {
        std::ostringstream size;
        size << r.width << "x" << r.height;
        s << std::left << std::setw(7) << r.group << std::setw(7) << r.view << std::setw(11) << size.str()
          << std::setw(14) << r.method << std::right << std::setw(2) << r.level << std::setprecision(1) << std::setw(6)
          << r.tolerance_px << std::setw(5)
          << (r.adaptive ? "on" : "off") << std::setw(5) << (r.culling ? "on" : "off") << std::setw(5)
          << (r.cropping ? "on" : "off") << std::setw(10) << r.cells << std::setprecision(1) << std::setw(12) << r.ms
          << std::setw(8) << r.tft << std::setw(8) << r.sil << std::setprecision(3) << std::setw(7) << r.p1
          << std::setw(6) << r.r1 << std::setw(6) << r.p2 << std::setw(6) << r.r2 << std::setprecision(2)
          << std::setw(6) << r.drawn_to_ref << std::setw(6) << r.ref_to_drawn << "\n";
    }
    return s.str();
}

std::vector<ChartSeries> bench_chart_series(const std::vector<BenchRow>& rows) {
    const std::vector<std::string> palette = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf"};
    std::vector<std::string> methods;  // one colour each, in order of appearance
    const std::vector<std::string> dashes = {"", "8,4", "2,3", "12,3,3,3", "6,2,1,2", "1,1"};
    std::vector<ChartSeries> series;
    std::vector<std::string> sizes;  // one dash per image size and tolerance
    for (const BenchRow& r : rows) {
        if (r.group != "sweep") continue;
        std::ostringstream tol;
        tol << r.tolerance_px;
        const std::string size = std::to_string(r.width) + "x" + std::to_string(r.height) + " tol " + tol.str() + " px";
        auto si = std::find(sizes.begin(), sizes.end(), size);
        if (si == sizes.end()) sizes.push_back(size), si = sizes.end() - 1;
        const std::string name = r.method + " " + size;
        auto it = std::find_if(series.begin(), series.end(), [&](const ChartSeries& c) { return c.name == name; });
        if (it == series.end()) {
            auto mi = std::find(methods.begin(), methods.end(), r.method);
            if (mi == methods.end()) methods.push_back(r.method), mi = methods.end() - 1;
            series.push_back({name, palette[std::size_t(mi - methods.begin()) % palette.size()],
                              dashes[std::size_t(si - sizes.begin()) % dashes.size()], {}});
            it = series.end() - 1;
        }
        it->points.push_back({r.ms, f1(r.p1, r.r1), r.ms_min, r.ms_max, "L" + std::to_string(r.level)});
    }
    return series;
}

namespace {

// One camera over one modelled terrain (set up for frames without creases or ridges: they cost
// the same in every row), with its exact reference silhouettes.
struct BenchView {
    std::string name;
    Camera camera;
    std::unique_ptr<TerrainFrames> frames;
    std::size_t cells = 0;
    std::vector<ImagePolyline> reference;
    double ref_ms = 0;
};

Scene silhouettes_only(const Scene& scene) {
    Scene s = scene;
    s.lines.creases.enabled = s.lines.ridges.enabled = false;
    return s;
}

std::unique_ptr<BenchView> make_view(const Scene& scene, const Terrain& dem, const std::optional<AnalyticCase>& analytic,
                                     GlContext& context, int w, int h, bool zoom, bool crop, const Log& log) {
    auto v = std::make_unique<BenchView>();
    Scene sized = silhouettes_only(scene);
    sized.view.camera.width = w, sized.view.camera.height = h;
    v->name = zoom ? "zoom4" : "scene";
    v->camera = analytic ? analytic->camera : scene_camera(sized, dem);
    v->camera.width = w, v->camera.height = h;
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
    v->frames = std::make_unique<TerrainFrames>(context, std::nullopt, std::move(t), w, h, log);
    return v;
}

// References: the closed form on an analytic terrain, else the ray-cast silhouettes of the
// full-resolution PN surface of the view's terrain window. Computed once per camera pose at the
// largest image size asked for; a smaller image of the same pose and aspect gets the same lines
// scaled (pixel coordinates scale with the image; the visibility does not change).
struct ReferenceCache {
    struct Entry {
        Camera camera;
        std::vector<ImagePolyline> lines;
        double ms = 0;
    };
    RaycastReferenceOptions rays;
    std::optional<AnalyticCase> analytic;
    std::vector<Entry> entries;

    static bool same_pose(const Camera& a, const Camera& b) {
        return a.eye == b.eye && a.azimuth == b.azimuth && a.altitude == b.altitude && a.fov == b.fov &&
               double(a.width) * b.height == double(a.height) * b.width;
    }
    const char* kind() const { return analytic ? "closed-form" : "ray-cast"; }
    void compute(const BenchView& v) {
        const auto t0 = Clock::now();
        entries.push_back({v.camera,
                           analytic ? analytic_silhouettes(analytic->shape, v.camera, false)
                                    : raycast_reference(mesh_from_terrain(window_terrain(v.frames->terrain())), v.camera, rays),
                           0});
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
void measure(BenchView& v, const Scene& frame, int frames, int warmup, const std::vector<ImagePolyline>& reference,
             const char* reference_kind, BenchRow& row) {
    for (int i = 0; i < warmup; ++i) v.frames->draw(v.camera, frame);
    std::vector<std::pair<double, PassTimings>> times;
    PixelMask last;
    for (int i = 0; i < std::max(1, frames); ++i) {
        const auto t0 = Clock::now();
        SceneDrawing d = v.frames->draw(v.camera, frame);
        times.emplace_back(ms_since(t0), d.times);
        last = std::move(d.silhouette_mask);
    }
    std::sort(times.begin(), times.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const auto& med = times[times.size() / 2];
    row.ms = med.first, row.tft = med.second.tft, row.aft = med.second.aft, row.sil = med.second.sil;
    row.ms_min = times.front().first, row.ms_max = times.back().first;
    const LineAccuracy a = line_accuracy(last, reference, {1.0, 2.0});
    row.p1 = a.at(1.0).precision, row.r1 = a.at(1.0).recall;
    row.p2 = a.at(2.0).precision, row.r2 = a.at(2.0).recall;
    row.drawn_to_ref = a.mean_drawn_to_reference, row.ref_to_drawn = a.mean_reference_to_drawn;
    row.view = v.name, row.cells = v.cells, row.ref_ms = v.ref_ms;
    row.reference = reference_kind;
    row.width = v.camera.width, row.height = v.camera.height;
}

struct BenchRun {
    const SpeedAccuracyConfig& config;
    const Scene& scene;
    const Terrain& dem;
    GlContext& context;
    const Log& log;
    ReferenceCache references;
    std::vector<BenchRow> rows;
};

void sweep(BenchRun& run) {
    const SpeedAccuracyConfig& c = run.config;
    const std::vector<float> tolerances = c.tolerances.empty() ? std::vector<float>{run.scene.terrain.surface_tolerance_px}
                                                               : c.tolerances;
    ProgressBar bar(std::cerr, run.log.progress, "bench",
                    int(tolerances.size() * c.sizes.size() * c.methods.size() * c.levels.size()));
    const auto largest = *std::max_element(c.sizes.begin(), c.sizes.end());
    run.references.compute(*make_view(run.scene, run.dem, run.config.analytic, run.context, largest.first, largest.second, false, true, run.log));
    for (const auto& [w, h] : c.sizes) {
        auto view = make_view(run.scene, run.dem, run.config.analytic, run.context, w, h, false, true, run.log);
        run.references.fill(*view);
        for (const float tolerance : tolerances) {
            for (const SilhouetteMethod m : c.methods) {
                for (std::size_t li = 0; li < c.levels.size(); ++li) {
                    const int level = c.levels[li];
                    Scene frame = silhouettes_only(run.scene);
                    frame.lines.silhouette_method = m;
                    frame.terrain.tess_max_level = level;
                    frame.terrain.surface_tolerance_px = tolerance;
                    BenchRow row;
                    row.group = "sweep", row.method = silhouette_method_name(m), row.level = level;
                    row.tolerance_px = tolerance;
                    // Every method timed on c.frames frames; programs warm up once per view and method.
                    measure(*view, frame, c.frames, li > 0 ? 0 : c.warmup, view->reference, run.references.kind(), row);
                    run.rows.push_back(row);
                    bar.step(row.method + " " + std::to_string(w) + "x" + std::to_string(h) + " L" +
                                 std::to_string(level), row.ms);
                }
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
        auto cropped = make_view(run.scene, run.dem, run.config.analytic, run.context, w, h, zoom, true, run.log);
        auto whole = make_view(run.scene, run.dem, run.config.analytic, run.context, w, h, zoom, false, run.log);
        run.references.fill(*cropped);
        bool warm_c = false, warm_w = false;  // warm up each view once
        for (const Config& c : configs) {
            bool& warm = c.cropping ? warm_c : warm_w;
            const int warmup = warm ? 0 : run.config.warmup;
            warm = true;
            Scene frame = silhouettes_only(run.scene);
            frame.lines.silhouette_method = SilhouetteMethod::toward_away;
            frame.terrain.tess_max_level = level;
            if (!c.adaptive) frame.terrain.tess_target_edge_px = 1e-3f;  // fixed: all at max
            frame.terrain.cull_patches = c.culling;
            BenchRow row;
            row.group = "needs", row.method = silhouette_method_name(frame.lines.silhouette_method), row.level = level;
            row.tolerance_px = frame.terrain.surface_tolerance_px;
            row.adaptive = c.adaptive, row.culling = c.culling, row.cropping = c.cropping;
            measure(c.cropping ? *cropped : *whole, frame, run.config.frames, warmup, cropped->reference, run.references.kind(), row);
            row.ref_ms = cropped->ref_ms;
            run.rows.push_back(row);
        }
    }
}

}  // namespace

std::vector<BenchRow> speed_accuracy_rows(const Scene& scene, const Terrain& dem, GlContext& context,
                                          const SpeedAccuracyConfig& config, const Log& log) {
    RaycastReferenceOptions rays;
    rays.edge_px = float(config.ref_edge_px), rays.rays.supersample = config.ref_supersample;
    BenchRun run{config, scene, dem, context, log, {rays, config.analytic, {}}, {}};
    sweep(run);
    if (config.needs) {
        const auto size = config.needs_size.first > 0 ? config.needs_size
                                                       : std::pair{scene.view.camera.width, scene.view.camera.height};
        needs_rows(run, *std::max_element(config.levels.begin(), config.levels.end()), size.first, size.second);
    }
    return run.rows;
}

}  // namespace penink
