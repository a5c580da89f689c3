// `penink fill DEM -o FILLED.tif [--band-rows N] [--max-memory M]`: CLI11 wiring of
// run_fill_command (scene/fill_command.hpp).
#pragma once
#include "cli/commands.hpp"

namespace penink {

Subcommand add_fill_command(CLI::App& app);

}  // namespace penink
