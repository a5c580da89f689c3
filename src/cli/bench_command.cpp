#include "cli/bench_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "scene/flight_coherence.hpp"
#include "scene/frame_source.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;
SilhouetteMethod parse_method(const std::string& m) {
    if (const auto method = silhouette_method_named(m)) return *method;
    throw Error("cli", "", "--methods: unknown method \"" + m + "\" (use toward-away, adjacency, edge-walk, object-space)");
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string f; std::getline(s, f, ',');) out.push_back(f);
    return out;
}

// Each comma-separated field of `text` read by parse(field, value) (false: not valid); one line
// naming the option and what a field must be otherwise, or for an empty list.
template <class T, class Parse>
std::vector<T> parse_list(const std::string& text, const std::string& option, const std::string& must_be, Parse parse) {
    std::vector<T> out;
    for (const std::string& f : split(text)) {
        T v{};
        if (f.empty() || !parse(f, v)) throw Error("cli", "", option + ": \"" + f + "\" is not " + must_be);
        out.push_back(v);
    }
    if (out.empty()) throw Error("cli", "", option + ": empty list");
    return out;
}

// The whole field as a number through std::stoi / std::stod.
template <class N, class Convert>
bool whole_number(const std::string& f, N& v, Convert convert) {
    std::size_t used = 0;
    try {
        v = N(convert(f, &used));
    } catch (const std::exception&) {
        return false;
    }
    return used == f.size();
}

}  // namespace

std::vector<int> parse_int_list(const std::string& text, const std::string& option) {
    return parse_list<int>(text, option, "a level between 1 and 64", [](const std::string& f, int& v) {
        return whole_number(f, v, [](const std::string& t, std::size_t* used) { return std::stoi(t, used); }) &&
               v >= 1 && v <= 64;
    });
}

std::vector<float> parse_tolerances(const std::string& text) {
    return parse_list<float>(text, "--tolerances", "a number of pixels between 0 and 1000",
                             [](const std::string& f, float& v) {
                                 double d = -1.0;
                                 const bool ok = whole_number(f, d, [](const std::string& t, std::size_t* used) {
                                     return std::stod(t, used);
                                 }) && d >= 0.0 && d <= 1000.0;
                                 v = float(d);
                                 return ok;
                             });
}

std::vector<std::pair<int, int>> parse_sizes(const std::string& text) {
    return parse_list<std::pair<int, int>>(text, "--sizes", "WIDTHxHEIGHT (8..8192 pixels)",
                                           [](const std::string& f, std::pair<int, int>& v) {
                                               int w = 0, h = 0;
                                               char x = 0, extra = 0;
                                               std::istringstream s(f);
                                               if (!(s >> w >> x >> h) || x != 'x' || (s >> extra) || w < 8 || h < 8 ||
                                                   w > 8192 || h > 8192)
                                                   return false;
                                               v = {w, h};
                                               return true;
                                           });
}

namespace {

template <class T, class Show>
std::string joined(const std::vector<T>& items, Show show) {
    std::string out;
    for (const T& item : items) out += (out.empty() ? "" : ",") + show(item);
    return out;
}

std::string size_text(const std::pair<int, int>& s) { return std::to_string(s.first) + "x" + std::to_string(s.second); }

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
    SpeedAccuracyConfig& c = o.config;
    const auto number = [](int v) { return std::to_string(v); };
    const auto method = [](SilhouetteMethod m) { return std::string(silhouette_method_name(m)); };
    CLI::App* cmd = app.add_subcommand(
        "bench", "Speed against accuracy of the silhouette methods: DIR/bench.csv, DIR/speed_accuracy.svg");
    cmd->add_option("input", o.input, "DEM or terrain scene file (.toml)");
    cmd->add_option("--flight", o.flight, "Flight path CSV: measure the frame-to-frame coherence of silhouettes and "
                                          "creases (share of drawn length persisting within 2 px) instead");
    cmd->add_option("--analytic", o.analytic, "Instead of input: an analytic terrain (" + analytic_case_names() + ")");
    cmd->add_option("--out", o.out_dir, "Output directory (created when missing)")->required();
    cmd->add_option("--levels", o.levels, "Tessellation max_level values (default " + joined(c.levels, number) + ")");
    cmd->add_option("--sizes", o.sizes, "Image sizes WxH (default " + joined(c.sizes, size_text) + ")");
    cmd->add_option("--tolerances", o.tolerances,
                    "Level-of-detail tolerances, pixels (0 = full resolution; default: the scene's [surface] tolerance_px)");
    cmd->add_option("--methods", o.methods, "Silhouette methods (default " + joined(c.methods, method) + ")");
    cmd->add_option("--frames", c.frames, "Frames timed per configuration, median reported")
        ->check(number_between(1, 10000))->capture_default_str();
    cmd->add_option("--warmup", c.warmup, "Untimed frames first")->check(number_between(0, 10000))->capture_default_str();
    cmd->add_option("--ref-edge-px", c.ref_edge_px, "Ray-cast reference: tessellated edges this long on screen at the largest size")
        ->check(positive_at_most(1000))->capture_default_str();
    cmd->add_option("--ref-supersample", c.ref_supersample, "Ray-cast reference: rays per pixel along x and y")
        ->check(number_between(1, 16))->capture_default_str();
    cmd->add_flag("!--no-needs", c.needs, "Leave out the culling / cropping / adaptive tessellation rows");
    cmd->add_option("--needs-size", o.needs_size, "Image size WxH of those rows (default: the scene's)");
    cmd->add_option("--gl", o.gl, "OpenGL backend: osmesa (software, default) or egl (GPU)")
        ->check(CLI::IsMember({"osmesa", "egl"}));
    add_log_flags(cmd, o.log, "Print modelled cells per view");
    return {cmd, [options] { return run_bench(*options); }};
}

int run_bench(const BenchOptions& o) {
    const Log log = o.log.log();
    SpeedAccuracyConfig config = o.config;
    if (!o.levels.empty()) config.levels = parse_int_list(o.levels, "--levels");
    if (!o.sizes.empty()) config.sizes = parse_sizes(o.sizes);
    if (!o.methods.empty()) {
        config.methods.clear();
        for (const std::string& m : split(o.methods)) config.methods.push_back(parse_method(m));
    }
    if (!o.tolerances.empty()) config.tolerances = parse_tolerances(o.tolerances);
    if (!o.needs_size.empty()) config.needs_size = parse_sizes(o.needs_size).front();
    if (o.input.empty() == o.analytic.empty()) throw Error("cli", "", "bench: give a DEM or scene file, or --analytic NAME");
    Scene scene;
    scene.terrain.exaggeration_auto = false;  // an analytic terrain is drawn as its closed form says
    Terrain dem;
    if (!o.analytic.empty()) {
        config.analytic = analytic_case(o.analytic, scene.view.camera.width, scene.view.camera.height);
        if (!config.analytic)
            throw Error("cli", "", "--analytic: unknown terrain \"" + o.analytic + "\" (use " + analytic_case_names() + ")");
        dem = analytic_grid(config.analytic->shape, config.analytic->spacing);
    } else {
        scene = bench_scene(o.input);
        dem = read_scene_dem(scene, log);
    }
    const std::string name = o.analytic.empty() ? fs::path(o.input).filename().string() : "analytic " + o.analytic;
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (!fs::is_directory(o.out_dir)) throw Error("bench", o.out_dir, "cannot create the output directory");
    const auto context = make_gl_context(parse_gl_backend(o.gl));
    if (!o.flight.empty()) {
        if (config.analytic) throw Error("cli", "", "--flight needs a DEM or scene file, not --analytic");
        const std::string csv = coherence_csv(flight_coherence(scene, o.flight, *context, 2.0, log));
        write_file_atomically((fs::path(o.out_dir) / "coherence.csv").string(), csv);
        std::cout << csv;
        return 0;
    }
    const std::vector<BenchRow> rows = speed_accuracy_rows(scene, dem, *context, config, log);
    write_file_atomically((fs::path(o.out_dir) / "bench.csv").string(), bench_csv(rows));
    ChartText text;
    text.title = "penink bench: " + name + ", silhouettes against the " +
                 (config.analytic ? "closed-form" : "ray-cast (" + std::to_string(config.ref_supersample) + "x)") +
                 " reference";
    text.subtitle = context->description();
    text.y_label = "silhouette accuracy: F1 of precision and recall at 1 px";
    write_speed_accuracy_chart((fs::path(o.out_dir) / "speed_accuracy.svg").string(), bench_chart_series(rows), text);
    std::cout << bench_table(rows);
    return 0;
}

}  // namespace penink
