#include "cli/preview_command.hpp"

#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "cli/scene_overrides.hpp"
#include "preview/preview_server.hpp"

namespace penink {

namespace {
struct PreviewOptions : SceneOverrides {
    int port = 0;
    std::string save;
    bool verbose = false;
};
}  // namespace

Subcommand add_preview_command(CLI::App& app) {
    auto options = std::make_shared<PreviewOptions>();
    PreviewOptions& o = *options;
    CLI::App* cmd = app.add_subcommand("preview", "Steer a terrain's view in the browser: a live drawing on a local web page");
    cmd->add_option("input", o.input, "DEM or terrain scene file (.toml)")->required();
    cmd->add_option("--port", o.port, "Port on 127.0.0.1 (default: a free one)")->check(number_between(1, 65535));
    cmd->add_option("--save", o.save, "Scene file the page's Save writes; Export writes beside it (default: NAME-view.toml here)");
    add_scene_override_options(cmd, o);
    cmd->add_flag("-v,--verbose", o.verbose, "Print each frame's passes and times");
    return {cmd, [options] {
                const PreviewOptions& given = *options;
                const Scene scene = load_scene_with_overrides(given);
                PreviewServerOptions server{given.port, given.save, parse_gl_backend(given.gl)};
                if (server.save_path.empty())
                    server.save_path = std::filesystem::path(given.input).stem().string() + "-view.toml";
                return serve_preview(scene, server, Log{given.verbose, ProgressMode::off}, std::cout);
            }};
}

}  // namespace penink
