#include "cli/render_command.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "scene/frame_source.hpp"
#include "scene/map_scale.hpp"
#include "scene/scene_inputs.hpp"
#include "core/error.hpp"
#include "core/huge_page_malloc.hpp"
#include "scene/frame_output.hpp"

namespace penink {

namespace {

PageOptions page_options(const RenderOptions& o) {
    PageOptions page;
    page.page = o.page, page.dpi = o.dpi, page.margin_mm = o.margin_mm;
    return page;
}

// Every output checked before anything is read or drawn (check_output_targets: formats, folders,
// page, PNG size at the scene's image size, checked again once the scene is loaded).
bool is_stdout(const std::string& path) { return path == "-" || path == "/dev/stdout"; }

// The output files, without the standard output.
std::vector<std::string> output_files(const RenderOptions& o) {
    std::vector<std::string> files;
    for (const std::string& p : o.outputs)
        if (!is_stdout(p)) files.push_back(p);
    return files;
}

void check_outputs(const RenderOptions& o, int width, int height) {
    if (o.outputs.empty()) throw Error("cli", "", "no output file given (use -o out.svg)");
    const std::vector<std::string> files = output_files(o);
    const std::size_t to_stdout = o.outputs.size() - files.size();
    if (to_stdout > 1) throw Error("cli", "", "standard output given more than once (-o -)");
    if (to_stdout == 1 && o.format.empty())
        throw Error("cli", "", "-o - writes to standard output: say its format with --format svg|ps|eps|pdf");
    if (to_stdout == 0 && !o.format.empty())
        throw Error("cli", "", "--format names the format of -o - (standard output), which is not among the outputs");
    if (!files.empty()) check_output_targets(files, page_options(o), width, height);
}


}  // namespace

Subcommand add_render_command(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    RenderOptions& o = *options;
    CLI::App* cmd = app.add_subcommand("render", "Draw a DEM, a mesh (OBJ/PLY/OFF) or a TOML scene as layered vector files");
    cmd->add_option("input", o.input, "DEM (GeoTIFF, ASCII grid, ...), mesh (.obj .ply .off) or scene file (.toml)")->required();
    cmd->add_option("-o,--output", o.outputs, "Output file, format from the extension: .svg .ps .eps .pdf, or a raster .png .tif .jpg .webp .exr (repeatable)")
        ->required();
    cmd->add_option("--page", o.page, "Physical page size: A4, A3, letter, WxHmm (default: image size at --dpi)");
    cmd->add_option("--dpi", o.dpi, "Image pixels per inch; also the resolution of raster outputs (default 96)")
        ->check(positive_at_most(10000));
    cmd->add_option("--margin", o.margin_mm, "Blank border on each side of the page, mm (default 0)")
        ->check(number_between(0, 1000));
    cmd->add_option("--layers", o.layers, "Layer split: kind, or kind+distance (near/middle/far sublayers)")
        ->check(CLI::IsMember({"kind", "kind+distance"}));
    add_scene_override_options(cmd, o);
    cmd->add_option("--format", o.format, "Format of -o - (standard output, for a pipe): svg, ps, eps or pdf")
        ->check(CLI::IsMember({"svg", "ps", "eps", "pdf"}));
    add_log_flags(cmd, o.log, "Print cells used, per-pass times and line statistics");
    return {cmd, [options] { return run_render(*options); }};
}

int run_render(const RenderOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    const Log log{o.log.verbose, progress_mode(o.log.quiet, o.log.progress || o.log.verbose)};  // -v: the builds' progress too
    check_outputs(o, o.width > 0 ? o.width : 1, o.height > 0 ? o.height : 1);
    if (heap_in_huge_pages()) log.info("heap in transparent huge pages (GLIBC_TUNABLES glibc.malloc.hugetlb)");
    Scene scene = load_scene_with_overrides(o);
    apply_map_scale(scene, page_options(o));
    check_outputs(o, scene.view.camera.width, scene.view.camera.height);
    check_outputs_are_not_inputs(output_files(o), scene_inputs(scene));  // before anything is written
    const auto context = make_gl_context(parse_gl_backend(o.gl));
    context->set_timed(log.verbose);  // the pass times are only logged
    log.info(context->description());
    FrameOutput output{output_files(o), page_options(o), parse_layer_split(o.layers), o.format, log.verbose, log.verbose};
    const RenderedFrame frame = render_scene_frame(scene, *context, output, log);
    const FrameOutputResult& written = frame.written;
    log_finish(written.finish, log);
    if (log.verbose && frame.terrain && !scene.source.dem.empty()) log_directions(frame.drawn.drawing, scene.source.dem, log);
    if (!o.format.empty()) {
        std::cout.write(written.document.data(), std::streamsize(written.document.size()));
        std::cout.flush();
        if (!std::cout) throw Error("export", "-", "cannot write to standard output");
    }
    const PlotStats& stats = written.plot;
    std::ostringstream s;
    s << stats.paths << " paths, " << stats.length_px << " px drawn, " << stats.travel_px << " px pen-up; "
      << "finished in " << std::lround(written.finish_ms) << " ms, written in " << std::lround(written.write_ms)
      << " ms; total " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s";
    log.info(s.str());
    for (const std::string& line : written.widths) log.info(line);
    return 0;
}

}  // namespace penink
