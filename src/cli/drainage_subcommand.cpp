#include "cli/drainage_subcommand.hpp"

#include <iostream>
#include <string>
#include <memory>

#include <CLI/CLI.hpp>

#include "scene/drainage_command.hpp"
#include "cli/option_checks.hpp"

namespace penink {

Subcommand add_drainage_command(CLI::App& app) {
    auto cmd_options = std::make_shared<DrainageCommand>();
    DrainageCommand& o = *cmd_options;
    CLI::App* cmd = app.add_subcommand(
        "drainage",
        "Build the drainage vertex database of a DEM (the cache render reads: DEM.dv), with the default "
        "options also the terrain cache (DEM.lod) and the crease tiles of the whole view (DEM.dv.tiles)");
    cmd->add_option("dem", o.dem, "DEM (GeoTIFF, ASCII grid, ...)")->required();
    cmd->add_option("-o,--output", o.output,
                    "Database file (default: the cache render reads, DEM.dv beside the DEM, or in the user cache "
                    "folder when the DEM's folder is read-only)");
    cmd->add_option("--resample", o.resample,
                    "Fine nodes per DEM cell side, 1..1000, within --max-memory (1 = the DEM's own nodes; default: 5, lowered to keep <= 4M points)")
        ->check(number_between(0, 1000));
    add_max_memory_option(cmd, o.max_memory);
    add_cache_dir_option(cmd, o.cache_dir);
    cmd->add_option("--rasters", o.rasters_dir,
                    "Also write GeoTIFFs (flow_direction ESRI D8, accumulation, basin, stream_order) to DIR");
    auto routing = std::make_shared<std::string>("priority-flood");
    cmd->add_option("--routing", *routing,
                    "Flow routing: priority-flood (default: fill, flats, ties) or least-cost "
                    "(the least-cost search of GRASS r.watershed -s)")
        ->check(CLI::IsMember({"priority-flood", "least-cost"}));
    cmd->add_flag("-q,--quiet", o.quiet, "No progress or summary lines");
    cmd->add_flag("-v,--verbose", o.verbose, "Also each stage's wall and CPU seconds");
    cmd->add_flag("--progress", o.progress, "Progress lines on stderr also when it is not a terminal");
    return {cmd, [cmd_options, routing] {
                cmd_options->routing = *drainage_routing_named(*routing);  // checked by IsMember
                return run_drainage_command(*cmd_options, std::cerr);
            }};
}

}  // namespace penink
