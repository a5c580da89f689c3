// Progress and --verbose messages of the command line, to stderr. Passed down explicitly.
#pragma once
#include <iostream>
#include <string>

namespace penink {

struct Log {
    bool verbose = false;
    void info(const std::string& msg) const {
        if (!verbose) return;
        // Messages that quote an error already carry the prefix.
        std::cerr << (msg.rfind("penink: ", 0) == 0 ? "" : "penink: ") << msg << "\n";
    }
};

}  // namespace penink
