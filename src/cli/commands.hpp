// The `penink` command line (CLI11): subcommands render, drainage, bench, batch. Returns the
// process exit code (0 ok, 2 bad input, 1 internal failure) after printing errors as one line.
#pragma once

namespace penink {

int run_cli(int argc, char** argv);

}  // namespace penink
