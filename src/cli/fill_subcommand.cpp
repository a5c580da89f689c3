#include "cli/fill_subcommand.hpp"

#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "scene/fill_command.hpp"

namespace penink {

Subcommand add_fill_command(CLI::App& app) {
    auto options = std::make_shared<FillCommand>();
    FillCommand& o = *options;
    CLI::App* cmd = app.add_subcommand(
        "fill", "Write the DEM with its depressions filled (Priority-Flood, a band of rows at a time: any size)");
    cmd->add_option("dem", o.dem, "DEM (GeoTIFF, ASCII grid, ...)")->required();
    cmd->add_option("-o,--output", o.output, "Filled DEM (Float32 GeoTIFF, metres, nodata NaN)")->required();
    cmd->add_option("--band-rows", o.band_rows, "Rows read and flooded at a time (default: about 4 M cells, within --max-memory)")
        ->check(number_between(0, 1 << 30));
    add_max_memory_option(cmd, o.max_memory);
    cmd->add_flag("-q,--quiet", o.quiet, "No progress or summary lines");
    cmd->add_flag("-v,--verbose", o.verbose, "Also the memory a band holds");
    cmd->add_flag("--progress", o.progress, "Progress lines on stderr also when it is not a terminal");
    return {cmd, [options] { return run_fill_command(*options, std::cerr); }};
}

}  // namespace penink
