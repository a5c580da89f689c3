#include "cli/commands.hpp"

#include <iostream>

#include <CLI/CLI.hpp>

namespace penink {

int run_cli(int argc, char** argv) {
    CLI::App app{"penink: pen-and-ink drawings of landscapes and models as layered vector files"};
    app.require_subcommand(1);
    CLI11_PARSE(app, argc, argv);
    return 0;
}

}  // namespace penink
