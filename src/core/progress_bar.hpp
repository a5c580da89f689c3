// Progress of a long command (batch frames, bench configurations) on stderr: on a terminal a
// bar redrawn in place ("\r[#####     ] 5/10 frame_0005 2.4 fps"), otherwise one plain line per
// step ("penink: batch: 5/10 frame_0005 412 ms"), so logs and pipes get no control characters.
#pragma once
#include <chrono>
#include <ostream>
#include <string>

namespace penink {

// How progress shows on stderr: not at all, redrawn in place (a terminal), or as plain lines.
enum class ProgressMode { off, terminal, lines };

// What the command line's flags ask for: -q turns progress off; otherwise it is drawn in place
// on a terminal, and as plain lines elsewhere only with --progress (logs and pipes stay clean).
ProgressMode progress_mode(bool quiet, bool asked);

// The text of one update. tty: "\r" + bar + counts + rate (no newline); else a full line.
std::string progress_text(const std::string& label, int done, int total, const std::string& item,
                          double step_ms, double elapsed_s, bool tty, int bar_width = 30);

class ProgressBar {
public:
    // `tty`: whether `out` is a terminal (isatty of stderr for the CLI): in place, else lines.
    ProgressBar(std::ostream& out, bool tty, std::string label, int total);
    ProgressBar(std::ostream& out, ProgressMode mode, std::string label, int total);
    // One step done: `item` names it, `step_ms` is its time.
    void step(const std::string& item, double step_ms);
    // Ends the bar's line on a terminal (nothing otherwise).
    void finish();

private:
    std::ostream* out_;
    bool tty_;
    bool on_ = true;
    std::string label_;
    int total_, done_ = 0;
    std::chrono::steady_clock::time_point start_;
};

// Progress of one long step through named stages, as a fraction done (a drainage database
// build): on a terminal "\rpenink: LABEL: STAGE  42%" redrawn in place and ended at 100 %;
// nothing otherwise, so logs and pipes stay clean.
// With ProgressMode::lines, one line each time the stage changes or another tenth is done.
class StageProgress {
public:
    StageProgress(std::ostream& out, bool tty, std::string label);
    StageProgress(std::ostream& out, ProgressMode mode, std::string label);
    void update(const std::string& stage, double fraction);

private:
    std::ostream* out_;
    ProgressMode mode_;
    std::string label_;
    std::string last_stage_;
    int last_tenth_ = -1;
};

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace penink
