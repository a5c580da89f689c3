#include "cli/option_checks.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/memory_budget.hpp"
#include "scene/map_scale.hpp"

namespace penink {

namespace {

// The value as a finite double; false for text that is not one.
bool finite_number(const std::string& text, double& v) {
    const char* b = text.data();
    const char* e = b + text.size();
    const auto [p, ec] = std::from_chars(b, e, v);
    return ec == std::errc() && p == e && std::isfinite(v);
}

// Quoted and cut short: the value as a message may show it.
std::string shown(const std::string& text) {
    std::string s;
    for (char c : text.substr(0, 40)) s += (c >= 0x20 && c < 0x7f) ? c : '?';
    return "\"" + s + (text.size() > 40 ? "...\"" : "\"");
}

}  // namespace

CLI::Validator number_between(double lo, double hi) {
    const std::string range = "between " + message_number(lo) + " and " + message_number(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            double v = 0.0;
            if (!finite_number(text, v) || v < lo || v > hi) return "must be " + range + " (got " + shown(text) + ")";
            return {};
        },
        "[" + message_number(lo) + ", " + message_number(hi) + "]");
}

CLI::Validator positive_at_most(double hi) {
    const std::string range = "> 0 and at most " + message_number(hi);
    return CLI::Validator(
        [hi, range](std::string& text) -> std::string {
            double v = 0.0;
            if (!finite_number(text, v) || !(v > 0.0) || v > hi) return "must be " + range + " (got " + shown(text) + ")";
            return {};
        },
        "(0, " + message_number(hi) + "]");
}

CLI::Validator map_scale_check() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            try {
                parse_map_scale(text);
            } catch (const std::invalid_argument&) {
                return "must be a map scale 1:N with N between 1 and 1e9, such as 1:25000 (got " + shown(text) + ")";
            }
            return {};
        },
        "1:N");
}

CLI::Validator positive_at_most_or_auto(double hi) {
    const CLI::Validator number = positive_at_most(hi);
    return CLI::Validator(
        [number](std::string& text) -> std::string {
            if (text == "auto") return {};
            std::string t = text;
            const std::string why = number(t);  // "must be > 0 and ..."
            return why.empty() ? why : "must be auto or " + why.substr(8);
        },
        "(0, " + message_number(hi) + "] or auto");
}

void add_cache_dir_option(CLI::App* cmd, std::string& dir) {
    cmd->add_option("--cache-dir", dir,
                    "Folder of the DEM's caches (.dv, .lod; default: beside the DEM when its folder is writable and "
                    "not installed, else $XDG_CACHE_HOME/penink or ~/.cache/penink)");
}

void add_max_memory_option(CLI::App* cmd, std::uint64_t& max_memory) {
    cmd->add_option_function<std::string>(
           "--max-memory",
           [&max_memory](const std::string& text) { max_memory = *parse_byte_size(text); },
           "Memory the command may use, e.g. 2G or 512M (default: what the system has available); an input "
           "that would need more is refused before it is read")
        ->type_name("SIZE")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                return parse_byte_size(text) ? std::string() : "expected a size such as 2G or 512M (got " + shown(text) + ")";
            },
            "SIZE"));
}

void add_log_flags(CLI::App* cmd, LogFlags& flags, const std::string& verbose_help) {
    cmd->add_flag("-v,--verbose", flags.verbose, verbose_help);
    cmd->add_flag("-q,--quiet", flags.quiet, "No progress");
    cmd->add_flag("--progress", flags.progress, "Progress lines on stderr also when it is not a terminal");
}

}  // namespace penink
