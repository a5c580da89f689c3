// Progress and --verbose messages of the command line, to stderr. Passed down explicitly.
#pragma once
#include <iostream>
#include <string>

namespace penink {

struct Log {
    bool verbose = false;
    void info(const std::string& msg) const { if (verbose) std::cerr << "penink: " << msg << "\n"; }
};

}  // namespace penink
