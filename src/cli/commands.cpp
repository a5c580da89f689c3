#include "cli/commands.hpp"

#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/render_command.hpp"
#include "core/error.hpp"

namespace penink {

int run_cli(int argc, char** argv) {
    CLI::App app{"penink: pen-and-ink drawings of landscapes and models as layered vector files"};
    app.require_subcommand(1);
    RenderOptions render;
    add_render_command(app, render);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);
        std::cerr << format_error("cli", "", e.what()) << "\n";
        return int(ExitCode::bad_input);
    }
    try {
        if (app.got_subcommand("render")) return run_render(render);
    } catch (const Error& e) {
        std::cerr << e.what() << "\n";
        return int(e.code());
    } catch (const std::exception& e) {
        std::cerr << format_error("internal", "", e.what()) << "\n";
        return int(ExitCode::internal);
    }
    return 0;
}

}  // namespace penink
