// penink command line entry point: dispatches to src/cli/commands (render, drainage, ...).
#include "cli/commands.hpp"

int main(int argc, char** argv) { return penink::run_cli(argc, argv); }
