// `penink render INPUT -o OUT...`: options, validation of outputs before any work, the terrain
// (or mesh) drawing, styling and export of every output file (format from its extension).
#pragma once
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace penink {

struct RenderOptions {
    std::string input;
    std::vector<std::string> outputs;
    std::string style;           // name or path; "" = the scene's
    std::string page;            // "A4", "WxHmm", "" = image size
    double dpi = 96.0;
    double margin_mm = 0.0;      // --margin: blank border on each side, mm
    std::string layers = "kind";  // "kind" or "kind+distance"
    std::string gl = "osmesa";
    bool verbose = false;
    // CLI overrides of scene values (unset = scene value)
    static constexpr int unset = -2147483647;
    int width = unset, height = unset;
    long long seed = -1;
    double vertical_exaggeration = 0.0;
};

Subcommand add_render_command(CLI::App& app);
int run_render(const RenderOptions& options);

}  // namespace penink
