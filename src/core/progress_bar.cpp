#include "core/progress_bar.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <unistd.h>

namespace penink {

std::string progress_text(const std::string& label, int done, int total, const std::string& item,
                          double step_ms, double elapsed_s, bool tty, int bar_width) {
    std::ostringstream s;
    s << std::fixed;
    if (!tty) {
        s.precision(0);
        s << "penink: " << label << ": " << done << "/" << total << " " << item << " " << step_ms << " ms\n";
        return s.str();
    }
    const int filled = total > 0 ? std::clamp(done * bar_width / total, 0, bar_width) : bar_width;
    s.precision(1);
    s << "\r" << label << " [" << std::string(std::size_t(filled), '#')
      << std::string(std::size_t(bar_width - filled), ' ') << "] " << done << "/" << total << " " << item;
    if (elapsed_s > 0.0) s << " " << done / elapsed_s << " per s";
    s << "\x1b[K";  // clear what a longer previous update left
    return s.str();
}

ProgressMode progress_mode(bool quiet, bool asked) {
    if (quiet) return ProgressMode::off;
    if (stderr_is_terminal()) return ProgressMode::terminal;
    return asked ? ProgressMode::lines : ProgressMode::off;
}

ProgressBar::ProgressBar(std::ostream& out, bool tty, std::string label, int total)
    : out_(&out), tty_(tty), label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()) {}

ProgressBar::ProgressBar(std::ostream& out, ProgressMode mode, std::string label, int total)
    : ProgressBar(out, mode == ProgressMode::terminal, std::move(label), total) {
    on_ = mode != ProgressMode::off;
}

void ProgressBar::step(const std::string& item, double step_ms) {
    ++done_;
    if (!on_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    *out_ << progress_text(label_, done_, total_, item, step_ms, elapsed, tty_) << std::flush;
}

void ProgressBar::finish() {
    if (on_ && tty_ && done_ > 0) *out_ << "\n" << std::flush;
}

StageProgress::StageProgress(std::ostream& out, bool tty, std::string label)
    : StageProgress(out, tty ? ProgressMode::terminal : ProgressMode::off, std::move(label)) {}

StageProgress::StageProgress(std::ostream& out, ProgressMode mode, std::string label)
    : out_(&out), mode_(mode), label_(std::move(label)) {}

void StageProgress::update(const std::string& stage, double fraction) {
    const int pct = int(fraction * 100.0 + 0.5);
    char line[160];
    if (mode_ == ProgressMode::terminal) {
        std::snprintf(line, sizeof line, "\rpenink: %s: %-12s %3d%%%s", label_.c_str(), stage.c_str(), pct,
                      fraction >= 1.0 ? "\n" : "");
        *out_ << line << std::flush;
    } else if (mode_ == ProgressMode::lines && (stage != last_stage_ || pct / 10 != last_tenth_)) {
        std::snprintf(line, sizeof line, "penink: %s: %s %d%%\n", label_.c_str(), stage.c_str(), pct);
        *out_ << line << std::flush;
        last_stage_ = stage, last_tenth_ = pct / 10;
    }
}

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) != 0; }

}  // namespace penink
