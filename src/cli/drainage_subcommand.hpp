// `penink drainage DEM [-o OUT.dv] [--resample F] [--rasters DIR] [--routing priority-flood|least-cost]`:
// CLI11 wiring of run_drainage_command (scene/drainage_command.hpp).
#pragma once
#include "cli/commands.hpp"

namespace penink {

Subcommand add_drainage_command(CLI::App& app);

}  // namespace penink
