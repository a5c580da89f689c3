// `penink preview SCENE_OR_DEM`: options (the scene overrides render takes, --port, --save) and
// the preview server (preview/preview_server.hpp).
#pragma once
#include "cli/commands.hpp"

namespace CLI {
class App;
}

namespace penink {

Subcommand add_preview_command(CLI::App& app);

}  // namespace penink
