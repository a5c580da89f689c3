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
#include "export/export_drawing.hpp"
#include "export/raster_writer.hpp"
#include "export/styled_drawing.hpp"
#include "lines/finish_drawing.hpp"
#include "scene/flight_frames.hpp"
#include "scene/scene_style.hpp"
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

Scene batch_scene(const BatchOptions& o) {
    Scene scene = load_scene_with_overrides(o);
    if (is_mesh_scene(scene)) throw Error("batch", o.input, "batch draws terrains (a DEM or a scene with [terrain])");
    return scene;
}

void write_text(const fs::path& p, const std::string& text) { write_file_atomically(p.string(), text); }

}  // namespace

double export_frame(Drawing& drawing, const Style& style, std::uint64_t seed, const std::vector<std::string>& paths) {
    const auto t0 = Clock::now();
    finish_drawing(drawing, finish_options(style, seed, true));
    const StyledDrawing styled = style_drawing(drawing, style, LayerSplit::kind);
    export_drawings(styled, PageOptions{}, paths);  // the frame's files together or none
    return ms_since(t0);
}

std::string timings_csv(const std::vector<FrameTiming>& frames) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    s << "frame,warmup,tft,aft,dm,sil,ridges,lay,readback,trace,total\n";
    for (const FrameTiming& f : frames) {
        const PassTimings& t = f.times;
        s << f.frame << "," << (f.warmup ? 1 : 0) << "," << t.tft << "," << t.aft << "," << t.dm << "," << t.sil
          << "," << t.ridges << "," << f.lay << "," << t.readback << "," << f.trace << "," << f.total << "\n";
    }
    return s.str();
}

namespace {

void table_row(std::ostream& s, const std::string& name, const std::vector<FrameTiming>& frames, bool warmup,
               double wall_s) {
    FrameTiming m;
    int n = 0;
    for (const FrameTiming& f : frames) {
        if (f.warmup != warmup) continue;
        ++n;
        m.times.tft += f.times.tft, m.times.aft += f.times.aft, m.times.dm += f.times.dm;
        m.times.sil += f.times.sil, m.times.ridges += f.times.ridges, m.times.readback += f.times.readback;
        m.lay += f.lay, m.trace += f.trace, m.total += f.total;
    }
    if (n == 0) return;
    const PassTimings& t = m.times;
    const double k = 1.0 / n;
    s << "| " << name << " | " << n << " | " << t.tft * k << " | " << t.aft * k << " | " << t.dm * k << " | "
      << t.sil * k << " | " << t.ridges * k << " | " << m.lay * k << " | " << t.readback * k << " | " << m.trace * k
      << " | " << m.total * k << " | " << 1000.0 / ((t.tft + t.dm) * k) << " | "
      << 1000.0 / ((t.tft + t.aft + t.sil) * k) << " | " << (wall_s > 0 ? n / wall_s : 0.0) << " |\n";
}

}  // namespace

std::string timings_markdown(const std::vector<FrameTiming>& frames, const BatchSummary& b) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1);
    s << "# penink batch timings\n\n"
      << "- scene: " << b.scene << ", " << b.width << "x" << b.height << " pixels\n"
      << "- machine: " << b.machine << "\n"
      << "- modelled: " << b.cells << " of " << b.dem_cells << " DEM cells; set-up " << std::setprecision(3)
      << b.setup_s << " s (DEM, mesh, GPU upload, drainage)\n" << std::setprecision(1)
      << "- mean ms per frame and pass; TFT holds the whole TFT+AFT pass when they run combined (AFT 0);"
         " LAY = finish, style and export of the frame's files; trace = images to polylines (CPU)\n"
      << "- CREASEfps = 1000/(TFT+DM), SILHfps = 1000/(TFT+AFT+SIL), TOTALfps = frames / wall seconds\n\n"
      << "| frames | n | TFT | AFT | DM | SIL | RIDGES | LAY | read-back | trace | total | CREASEfps | SILHfps | TOTALfps |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    table_row(s, "warm-up", frames, true, b.warmup_wall_s);
    table_row(s, "after warm-up", frames, false, b.frames_wall_s);
    return s.str();
}

Subcommand add_batch_command(CLI::App& app) {
    auto options = std::make_shared<BatchOptions>();
    BatchOptions& o = *options;
    CLI::App* cmd = app.add_subcommand(
        "batch",
        "Draw one frame per record of a flight path (animation); frames DIR/frame_0001.png/.svg and timings.\n"
        "The CSV and every camera are checked before the first frame is drawn: a bad path writes nothing.\n"
        "Frames are written whole (atomically); a run stopped part way leaves frame_0001..k complete.");
    cmd->add_option("input", o.input, "DEM or terrain scene file (.toml)")->required();
    cmd->add_option("--path", o.path,
                    "Flight path CSV with a header row. Columns: position (\"E N 18N\", \"lon,lat\" quoted, or \"x y\"), "
                    "elevation (m), azimuth, altitude (deg); optional light_azimuth, light_altitude (deg), min_score "
                    "(crease threshold); an empty optional cell keeps the scene's value")
        ->required();
    cmd->add_option("--out", o.out_dir, "Output directory (created when missing)")->required();
    cmd->add_option("--formats", o.formats, "Comma-separated frame formats: svg, ps, eps, pdf, or a raster png, tif, jpg, webp, exr (default png,svg)");
    cmd->add_option("--warmup", o.warmup, "First N frames timed apart (shader JIT, caches); default 1")
        ->check(number_between(0, 1000000));
    cmd->add_flag("--whole-dem", o.whole_dem, "Model the whole DEM (default: the union of the frames' visible windows)");
    cmd->add_option("--shard", o.shard,
                    "K/N: draw only frames K, K+N, K+2N, ... (one of N machines or jobs); the frames are the same "
                    "bytes as an unsharded run's; timings go to timings_K-of-N.csv/.md");
    add_scene_override_options(cmd, o);
    cmd->add_flag("-v,--verbose", o.verbose, "Print the modelled cells and set-up steps");
    cmd->add_flag("-q,--quiet", o.quiet, "No progress");
    cmd->add_flag("--progress", o.progress, "Progress lines on stderr also when it is not a terminal");
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

int run_batch(const BatchOptions& o) {
    const auto start = Clock::now();
    const Log log{o.verbose, progress_mode(o.quiet, o.progress)};
    int shard = 1, shards = 1;
    parse_shard(o.shard, shard, shards);
    const std::vector<std::string> formats = parse_formats(o.formats);
    Scene scene = batch_scene(o);
    const Style style = scene_style(scene);
    apply_object_sketch(scene, style);
    Flight f = plan_flight(scene, o.path, o.whole_dem, log);
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (!fs::is_directory(o.out_dir)) throw Error("batch", o.out_dir, "cannot create the output directory");
    check_output_targets(frame_paths(o.out_dir, 1, formats), PageOptions{}, scene.camera.width, scene.camera.height);
    const auto context = make_gl_context(parse_gl_backend(o.gl));
    BatchSummary summary;
    summary.machine = context->description(), summary.scene = o.input;
    summary.width = scene.camera.width, summary.height = scene.camera.height;
    summary.cells = f.model.cells();
    summary.dem_cells = std::size_t(f.dem.stored.meta.cols - 1) * (f.dem.stored.meta.rows - 1);
    TerrainFrames frames(*context, scene_drainage(scene, f.dem, log), std::move(f.model), summary.width, summary.height,
                         log, LineCulling{f.cameras, line_culling_px(scene)});
    summary.setup_s = ms_since(start) / 1000.0;
    std::vector<FrameTiming> timings;
    // A shard draws its frames from the whole flight's set-up (window, depth range, line culling
    // for every camera), so each frame is what an unsharded run draws.
    const int drawn = (int(f.records.size()) - shard) / shards + 1;
    ProgressBar bar(std::cerr, log.progress, "batch", std::max(drawn, 0));
    for (std::size_t i = std::size_t(shard - 1); i < f.records.size(); i += std::size_t(shards)) {
        const auto t0 = Clock::now();
        FrameTiming t;
        t.frame = int(i) + 1, t.warmup = int(i) < o.warmup;
        SceneDrawing d = frames.draw(f.cameras[i], frame_scene(scene, f.records[i]));
        t.times = d.times, t.trace = d.trace_ms;
        t.lay = export_frame(d.drawing, style, scene.seed, frame_paths(o.out_dir, t.frame, formats));
        t.total = ms_since(t0);
        (t.warmup ? summary.warmup_wall_s : summary.frames_wall_s) += t.total / 1000.0;
        timings.push_back(t);
        bar.step(fs::path(frame_paths(o.out_dir, t.frame, formats)[0]).stem().string(), t.total);
    }
    bar.finish();
    const std::string stem = shards > 1 ? "timings_" + std::to_string(shard) + "-of-" + std::to_string(shards) : "timings";
    write_text(fs::path(o.out_dir) / (stem + ".csv"), timings_csv(timings));
    const std::string md = timings_markdown(timings, summary);
    write_text(fs::path(o.out_dir) / (stem + ".md"), md);
    std::cout << md;
    return 0;
}

}  // namespace penink
