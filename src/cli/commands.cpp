#include "cli/commands.hpp"

#include <system_error>

#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/batch_command.hpp"
#include "cli/bench_command.hpp"
#include "cli/drainage_subcommand.hpp"
#include "cli/fill_subcommand.hpp"
#include "cli/preview_command.hpp"
#include "cli/render_command.hpp"
#include "core/error.hpp"
#include "core/version.hpp"

namespace penink {

namespace {

std::vector<Subcommand> register_subcommands(CLI::App& app) {
    std::vector<Subcommand> subs;
    subs.push_back(add_render_command(app));
    subs.push_back(add_drainage_command(app));
    subs.push_back(add_fill_command(app));
    subs.push_back(add_bench_command(app));
    subs.push_back(add_batch_command(app));
    subs.push_back(add_preview_command(app));
    // One line per subcommand (keep this list in this order): render, drainage, fill, bench, batch, preview.
    return subs;
}

}  // namespace

int run_cli(int argc, char** argv) {
    CLI::App app{"penink: pen-and-ink drawings of landscapes and models as layered vector files"};
    app.set_version_flag("--version", std::string("penink ") + penink_version, "Print the version and exit");
    app.require_subcommand(1);
    const std::vector<Subcommand> subs = register_subcommands(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);
        std::cerr << format_error("cli", "", e.what()) << "\n";
        return int(ExitCode::bad_input);
    }
    try {
        for (const Subcommand& s : subs)
            if (s.app->parsed()) return s.run();
    } catch (const Error& e) {
        std::cerr << e.what() << "\n";
        return int(e.code());
    } catch (const std::system_error& e) {
        // a thread or resource the process limits refuse (ulimit -u): the environment's, not penink's
        if (e.code() == std::errc::resource_unavailable_try_again) {
            std::cerr << format_error("cli", "", std::string("cannot start a thread (") + e.what() +
                                                    "): raise the process limit (ulimit -u)") << "\n";
            return int(ExitCode::bad_input);
        }
        std::cerr << format_error("internal", "", e.what()) << "\n";
        return int(ExitCode::internal);
    } catch (const std::exception& e) {
        std::cerr << format_error("internal", "", e.what()) << "\n";
        return int(ExitCode::internal);
    }
    return 0;
}

}  // namespace penink
