// Progress and --verbose messages of the command line, to stderr. Passed down explicitly.
#pragma once
#include <iostream>
#include <string>

#include "core/progress_bar.hpp"

namespace penink {

struct Log {
    bool verbose = false;
    ProgressMode progress = ProgressMode::off;  // how long steps show their progress (progress_mode)
    void info(const std::string& msg) const {
        if (!verbose) return;
        // Messages that quote an error already carry the prefix.
        std::cerr << (msg.rfind("penink: ", 0) == 0 ? "" : "penink: ") << msg << "\n";
    }
};

}  // namespace penink
