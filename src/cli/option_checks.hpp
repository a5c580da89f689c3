// Checks of command-line values with short, readable messages (CLI11's own ranges print
// std::to_string of their bounds: "not in range 0.000000 to 1797...", a 309-digit number): a
// number within [lo, hi] or (0, hi], and the --max-memory option (a byte size such as 2G or
// 512M, core/memory_budget.hpp) of the commands that read DEMs; the log flags every drawing
// command takes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/log.hpp"

namespace penink {

// "must be between LO and HI (got X)": finite, lo <= x <= hi.
CLI::Validator number_between(double lo, double hi);
// "must be > 0 and at most HI (got X)": finite, 0 < x <= hi.
CLI::Validator positive_at_most(double hi);

// positive_at_most, or the word "auto".
CLI::Validator positive_at_most_or_auto(double hi);

// "must be a map scale such as 1:25000": parse_map_scale accepts it.
CLI::Validator map_scale_check();

// --max-memory SIZE into `max_memory` (bytes; left 0 when not given = the memory available).
void add_max_memory_option(CLI::App* cmd, std::uint64_t& max_memory);
// --cache-dir DIR into `dir`: the folder of the DEM's caches (drainage_cache_path).
void add_cache_dir_option(CLI::App* cmd, std::string& dir);

// -v/--verbose (its help text `verbose_help`), -q/--quiet, --progress of render, batch and bench.
struct LogFlags {
    bool verbose = false;
    bool quiet = false;     // no progress
    bool progress = false;  // progress lines also when stderr is not a terminal
    Log log() const { return Log{verbose, progress_mode(quiet, progress)}; }
};
void add_log_flags(CLI::App* cmd, LogFlags& flags, const std::string& verbose_help);

}  // namespace penink
