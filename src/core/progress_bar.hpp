// Progress of a long command (batch frames, bench configurations) on stderr: on a terminal a
// bar redrawn in place ("\r[#####     ] 5/10 frame_0005 2.4 fps"), otherwise one plain line per
// step ("penink: batch: 5/10 frame_0005 412 ms"), so logs and pipes get no control characters.
#pragma once
#include <chrono>
#include <ostream>
#include <string>

namespace penink {

// The text of one update. tty: "\r" + bar + counts + rate (no newline); else a full line.
std::string progress_text(const std::string& label, int done, int total, const std::string& item,
                          double step_ms, double elapsed_s, bool tty, int bar_width = 30);

class ProgressBar {
public:
    // `tty`: whether `out` is a terminal (isatty of stderr for the CLI).
    ProgressBar(std::ostream& out, bool tty, std::string label, int total);
    // One step done: `item` names it, `step_ms` is its time.
    void step(const std::string& item, double step_ms);
    // Ends the bar's line on a terminal (nothing otherwise).
    void finish();

private:
    std::ostream* out_;
    bool tty_;
    std::string label_;
    int total_, done_ = 0;
    std::chrono::steady_clock::time_point start_;
};

// Progress of one long step through named stages, as a fraction done (a drainage database
// build): on a terminal "\rpenink: LABEL: STAGE  42%" redrawn in place and ended at 100 %;
// nothing otherwise, so logs and pipes stay clean.
class StageProgress {
public:
    StageProgress(std::ostream& out, bool tty, std::string label);
    void update(const std::string& stage, double fraction);

private:
    std::ostream* out_;
    bool tty_;
    std::string label_;
};

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace penink
