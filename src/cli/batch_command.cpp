#include "cli/batch_command.hpp"

#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "core/error.hpp"
#include "core/progress_bar.hpp"
#include "core/stopwatch.hpp"
#include "export/atomic_file.hpp"
#include "export/raster_writer.hpp"
#include "scene/frame_output.hpp"
#include "scene/flight_frames.hpp"
#include "scene/mesh_frames.hpp"
#include "scene/scene_inputs.hpp"
#include "scene/terrain_frames.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> parse_formats(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string f; std::getline(s, f, ',');) {
        if (f != "svg" && f != "ps" && f != "eps" && f != "pdf" && !is_raster_extension("." + f)) {
            std::string known = "svg, ps, eps, pdf";
            for (const std::string& e : raster_extensions()) known += ", " + e.substr(1);
            throw Error("cli", "", "--formats: unknown format \"" + f + "\" (use " + known + ")");
        }
        out.push_back(f);
    }
    if (out.empty()) throw Error("cli", "", "--formats: no format given");
    return out;
}

void write_text(const fs::path& p, const std::string& text) { write_file_atomically(p.string(), text); }

}  // namespace

Subcommand add_batch_command(CLI::App& app) {
    auto options = std::make_shared<BatchOptions>();
    BatchOptions& o = *options;
    CLI::App* cmd = app.add_subcommand(
        "batch",
        "Draw one frame per record of a flight path over a terrain, or per step of an orbit around a mesh\n"
        "(animation); frames DIR/frame_0001.png/.svg and the timing tables (DIR/timings.csv, .md).\n"
        "The CSV and every camera are checked before the first frame is drawn: a bad path writes nothing.\n"
        "Frames are written whole (atomically); a run stopped part way leaves frame_0001..k complete.");
    cmd->add_option("input", o.input, "DEM, mesh (.obj .ply .off) or scene file (.toml)")->required();
    cmd->add_option("--path", o.path,
                    "A terrain's flight path CSV with a header row. Columns: position (\"E N 18N\", \"lon,lat\" quoted, or \"x y\"), "
                    "elevation (m), azimuth, altitude (deg); optional light_azimuth, light_altitude (deg), min_score "
                    "(crease threshold); an empty optional cell keeps the scene's value");
    cmd->add_option("--orbit", o.orbit,
                    "A mesh's walk-through: N frames orbiting the model from the scene's camera, 360/N degrees apart "
                    "about the vertical through the point it looks at")
        ->check(number_between(1, 1000000));
    cmd->add_option("--out", o.out_dir, "Output directory (created when missing)")->required();
    cmd->add_option("--formats", o.formats, "Comma-separated frame formats: svg, ps, eps, pdf, or a raster png, tif, jpg, webp, exr (default png,svg)");
    cmd->add_option("--warmup", o.warmup, "First N frames this run draws timed apart (shader JIT, caches); default 3")
        ->check(number_between(0, 1000000));
    cmd->add_flag("--whole-dem", o.whole_dem, "Model the whole DEM (default: the union of the frames' visible windows)");
    cmd->add_option("--shard", o.shard,
                    "K/N: draw only frames K, K+N, K+2N, ... (one of N machines or jobs); the frames are the same "
                    "bytes as an unsharded run's; timings go to timings_K-of-N.csv/.md");
    add_scene_override_options(cmd, o);
    add_log_flags(cmd, o.log, "Print the modelled cells and set-up steps");
    return {cmd, [options] { return run_batch(*options); }};
}

namespace {

std::vector<std::string> frame_paths(const fs::path& dir, int frame, const std::vector<std::string>& formats) {
    std::ostringstream name;
    name << "frame_" << std::setw(4) << std::setfill('0') << frame;
    std::vector<std::string> paths;
    for (const std::string& f : formats) paths.push_back((dir / (name.str() + "." + f)).string());
    return paths;
}

}  // namespace

void parse_shard(const std::string& text, int& k, int& n) {
    k = 1, n = 1;
    if (text.empty()) return;
    const std::size_t slash = text.find('/');
    char* end = nullptr;
    const long kk = slash == std::string::npos ? 0 : std::strtol(text.c_str(), &end, 10);
    const bool k_ok = slash != std::string::npos && end == text.c_str() + slash && slash > 0;
    const long nn = k_ok ? std::strtol(text.c_str() + slash + 1, &end, 10) : 0;
    if (!k_ok || *end != '\0' || slash + 1 == text.size() || nn < 1 || nn > 1000000 || kk < 1 || kk > nn)
        throw Error("cli", "", "--shard must be K/N with 1 <= K <= N <= 1000000, got \"" + text + "\"");
    k = int(kk), n = int(nn);
}

namespace {

// What a run flies: one camera per frame, the frames' source, and (a terrain) the flight records
// with their per-frame scene values.
struct BatchFlight {
    std::vector<Camera> cameras;
    std::vector<FlightRecord> records;  // empty for an orbit
    std::unique_ptr<FrameSource> frames;
};

// Checks that --path / --orbit / --whole-dem fit the scene's input.
void check_flight_options(const BatchOptions& o, bool mesh) {
    if (mesh && !o.path.empty())
        throw Error("batch", o.path, "a flight path flies over a terrain; a mesh scene takes --orbit N");
    if (mesh && o.orbit == 0) throw Error("batch", o.input, "a mesh scene needs --orbit N (frames around the model)");
    if (mesh && o.whole_dem) throw Error("batch", o.input, "--whole-dem: a mesh scene has no DEM");
    if (!mesh && o.orbit > 0) throw Error("batch", o.input, "--orbit flies around a mesh; a terrain takes --path CSV");
    if (!mesh && o.path.empty()) throw Error("batch", o.input, "a terrain needs --path CSV (the flight path)");
}

// The output folder, made and checked before anything is drawn.
void prepare_out_dir(const BatchOptions& o, const std::vector<std::string>& formats, const Scene& scene) {
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (!fs::is_directory(o.out_dir)) throw Error("batch", o.out_dir, "cannot create the output directory");
    check_output_targets(frame_paths(o.out_dir, 1, formats), PageOptions{}, scene.view.camera.width, scene.view.camera.height);
}

}  // namespace

int run_batch(const BatchOptions& o) {
    const auto start = Clock::now();
    const Log log = o.log.log();
    int shard = 1, shards = 1;
    parse_shard(o.shard, shard, shards);
    const std::vector<std::string> formats = parse_formats(o.formats);
    Scene scene = load_scene_with_overrides(o);
    BatchSummary summary;
    summary.mesh = is_mesh_scene(scene);
    check_flight_options(o, summary.mesh);
    const Style& style = scene.style.resolved;
    summary.scene = o.input, summary.warmup = o.warmup;
    summary.width = scene.view.camera.width, summary.height = scene.view.camera.height;
    std::unique_ptr<GlContext> context;  // outlives the frames' GL objects
    BatchFlight flight;
    if (summary.mesh) {
        context = make_gl_context(parse_gl_backend(o.gl));
        auto mesh = std::make_unique<MeshFrames>(scene, *context, log);
        flight.cameras = mesh->orbit(scene, o.orbit);
        summary.triangles = mesh->triangles();
        flight.frames = std::move(mesh);
        prepare_out_dir(o, formats, scene);
    } else {
        Flight f = plan_flight(scene, o.path, o.whole_dem, log);
        prepare_out_dir(o, formats, scene);
        context = make_gl_context(parse_gl_backend(o.gl));
        summary.cells = f.model.cells();
        summary.dem_cells = std::size_t(f.dem.stored.meta.cols - 1) * (f.dem.stored.meta.rows - 1);
        flight.frames = std::make_unique<TerrainFrames>(*context, scene_drainage(scene, f.dem, log), std::move(f.model),
                                                        summary.width, summary.height, log,
                                                        LineCulling{f.cameras, line_culling_px(scene)});
        flight.cameras = std::move(f.cameras), flight.records = std::move(f.records);
    }
    summary.machine = context->description();
    summary.setup_s = ms_since(start) / 1000.0;
    std::vector<FrameTiming> timings;
    // A shard draws its frames from the whole flight's set-up (window, depth range, line culling
    // for every camera), so each frame is what an unsharded run draws. Warm-up: the first frames
    // this run draws (its shader JIT and caches).
    const std::size_t count = flight.cameras.size();
    const std::string stem = shards > 1 ? "timings_" + std::to_string(shard) + "-of-" + std::to_string(shards) : "timings";
    {  // no frame or table replaces an input (a DEM or flight path kept in the output folder)
        std::vector<std::string> outs = {(fs::path(o.out_dir) / (stem + ".csv")).string(),
                                         (fs::path(o.out_dir) / (stem + ".md")).string()};
        for (std::size_t i = 0; i < count; ++i)
            for (std::string& p : frame_paths(o.out_dir, int(i) + 1, formats)) outs.push_back(std::move(p));
        std::vector<NamedInput> inputs = scene_inputs(scene);
        if (!o.path.empty()) inputs.push_back({o.path, "the flight path"});
        check_outputs_are_not_inputs(outs, inputs);
    }
    const int drawn = (int(count) - shard) / shards + 1;
    ProgressBar bar(std::cerr, log.progress, "batch", std::max(drawn, 0));
    for (std::size_t i = std::size_t(shard - 1); i < count; i += std::size_t(shards)) {
        const auto t0 = Clock::now();
        FrameTiming t;
        t.frame = int(i) + 1, t.warmup = int(timings.size()) < o.warmup;
        SceneDrawing d = flight.frames->draw(flight.cameras[i],
                                             flight.records.empty() ? scene : frame_scene(scene, flight.records[i]));
        t.times = d.times, t.lines = d.lines, t.trace = d.trace_ms;
        FrameOutput output{frame_paths(o.out_dir, t.frame, formats), {}, LayerSplit::kind, ""};
        output.furniture = scene.view.furniture, output.map_scale = scene.view.map_scale;
        const FrameOutputResult e = write_frame(d.drawing, style, scene.style.seed, !summary.mesh, output);
        t.finish = e.finish_ms, t.write = e.write_ms;
        t.total = ms_since(t0);
        timings.push_back(t);
        bar.step(fs::path(frame_paths(o.out_dir, t.frame, formats)[0]).stem().string(), t.total);
    }
    bar.finish();
    write_text(fs::path(o.out_dir) / (stem + ".csv"), timings_csv(timings, summary.mesh));
    const std::string md = timings_markdown(timings, summary);
    write_text(fs::path(o.out_dir) / (stem + ".md"), md);
    std::cout << md;
    return 0;
}

}  // namespace penink
