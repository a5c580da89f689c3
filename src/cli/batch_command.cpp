#include "cli/batch_command.hpp"

#include <cstdlib>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "core/error.hpp"
#include "core/stopwatch.hpp"
#include "export/raster_writer.hpp"
#include "scene/batch_run.hpp"

namespace penink {

namespace {

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
    const Log log = o.log.log();
    BatchRun run{o.input, o.path, o.orbit, o.out_dir, {}, o.warmup, o.whole_dem};
    parse_shard(o.shard, run.shard, run.shards);
    run.formats = parse_formats(o.formats);
    Scene scene = load_scene_with_overrides(o);
    run.gl = parse_gl_backend(o.gl);
    std::cout << run_batch_frames(scene, run, start, log);
    return 0;
}

}  // namespace penink
