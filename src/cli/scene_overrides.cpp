#include "cli/scene_overrides.hpp"

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"

namespace penink {

void add_scene_override_options(CLI::App* cmd, SceneOverrides& o) {
    cmd->add_option("--style", o.style, "Style name (technical, field-sketch, plotter) or a style .toml file");
    cmd->add_option("--width", o.width, "Image width in pixels, 1..16384 (overrides the scene)")
        ->check(number_between(1, max_image_side));
    cmd->add_option("--height", o.height, "Image height in pixels, 1..16384 (overrides the scene)")
        ->check(number_between(1, max_image_side));
    cmd->add_option("--seed", o.seed, "Seed of the sketchy perturbation (same seed, same output)")
        ->check(number_between(0, 9007199254740992.0));
    cmd->add_option("--vertical-exaggeration", o.vertical_exaggeration,
                    "Scale elevations by this factor, (0, 1000], or auto (from the relief and extent; the default for DEMs)")
        ->check(positive_at_most_or_auto(max_vertical_exaggeration));
    cmd->add_flag("--map", o.map, "Orthographic plan view of the whole DEM, north up");
    cmd->add_option("--scale", o.scale, "Map scale 1:N on the page set by --page/--dpi/--margin (orthographic views)")
        ->check(map_scale_check());
    cmd->add_option("--title", o.title, "Map title, drawn in a plan view's title layer ([map] title)");
    cmd->add_option("--grid", o.grid, "Grid ticks on a plan view's neatline: none, map (map CRS) or graticule (lon/lat)")
        ->check(CLI::IsMember({"none", "map", "graticule"}));
    cmd->add_flag("--no-furniture", o.no_furniture, "No neatline, scale bar, north arrow, grid or title on a plan view");
    cmd->add_option("--sea-level", o.sea_level,
                    "Draw the DEM below this elevation (its units, unexaggerated) as water, with a coastline")
        ->check(number_between(-1e7, 1e7));
    cmd->add_option("--gl", o.gl, "OpenGL backend: osmesa (software, default) or egl (GPU)")
        ->check(CLI::IsMember({"osmesa", "egl"}));
    add_max_memory_option(cmd, o.max_memory);
    add_cache_dir_option(cmd, o.cache_dir);
    const char* place = "(\"LON,LAT\", \"EASTING NORTHING ZONE\" such as \"588497 4589846 18N\", or \"X Y\" in the DEM's CRS)";
    cmd->add_option("--position", o.position, std::string("Camera position ") + place + "; goes with --elevation");
    cmd->add_option("--elevation", o.elevation, "Camera elevation, metres above the DEM's datum (unexaggerated)")
        ->check(number_between(-1e7, 1e7));
    cmd->add_option("--azimuth", o.azimuth, "View direction, degrees clockwise from grid north")
        ->check(number_between(-360, 360));
    cmd->add_option("--altitude", o.altitude, "View direction above the horizontal, degrees (negative looks down)")
        ->check(number_between(-90, 90));
    cmd->add_option("--fov", o.fov, "Horizontal field of view, degrees")->check(number_between(0.001, 178.999));
    cmd->add_option("--target", o.target,
                    std::string("A place to look at ") + place +
                        ": aimed at from --position, or seen from --distance along --azimuth/--altitude");
    cmd->add_option("--distance", o.distance, "Metres from the camera to --target (default: half the DEM's extent)")
        ->check(number_between(1e-3, 1e8));
}

}  // namespace penink
