// penink command line entry point: dispatches to src/cli/commands (render, drainage, ...).
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "cli/commands.hpp"

// Every file is closed by the time run_cli returns: the process then ends without the libraries'
// teardown at exit (GDAL's drivers, PROJ's database: a few milliseconds of every command).
int main(int argc, char** argv) {
    const int code = penink::run_cli(argc, argv);
    std::cout.flush(), std::cerr.flush();
    std::fflush(nullptr);
    std::_Exit(code);
}
