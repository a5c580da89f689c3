// `penink render INPUT -o OUT...`: options, validation of outputs before any work, the terrain
// (or mesh) drawing, styling and export of every output file (format from its extension).
#pragma once
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/scene_overrides.hpp"

namespace penink {

struct RenderOptions : SceneOverrides {
    std::vector<std::string> outputs;
    std::string page;            // "A4", "WxHmm", "" = image size
    double dpi = 96.0;
    double margin_mm = 0.0;      // --margin: blank border on each side, mm
    std::string layers = "kind";  // "kind" or "kind+distance"
    std::string format;          // of the output "-" (standard output): svg, ps, eps or pdf
    LogFlags log;
};

Subcommand add_render_command(CLI::App& app);
int run_render(const RenderOptions& options);

}  // namespace penink
