// The `penink` command line (CLI11): subcommands render, drainage, bench, batch. Returns the
// process exit code (0 ok, 2 bad input, 1 internal failure) after printing errors as one line.
#pragma once
#include <functional>

namespace CLI {
class App;
}

namespace penink {

// A subcommand registers its options on the parent app and returns what runs it when chosen
// (the exit code). Options live in the closure, so no state is shared between subcommands.
struct Subcommand {
    CLI::App* app = nullptr;
    std::function<int()> run;
};

int run_cli(int argc, char** argv);

}  // namespace penink
