#include "core/error.hpp"

#include <cstdio>

namespace penink {

std::string message_number(double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%g", v);
    return s;
}

std::string format_error(const std::string& stage, const std::string& file, const std::string& what) {
    std::string s = "penink: " + stage + ": ";
    if (!file.empty()) s += file + ": ";
    return s + what;
}

Error::Error(std::string stage, std::string file, const std::string& what, ExitCode code)
    : std::runtime_error(format_error(stage, file, what)),
      stage_(std::move(stage)), file_(std::move(file)), code_(code) {}

}  // namespace penink
