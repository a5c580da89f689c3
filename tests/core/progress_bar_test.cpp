// Progress modes: off draws nothing; lines mode writes a plain line when the stage changes or
// another tenth is done (no carriage returns); terminal mode redraws one line in place; -q wins.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "core/progress_bar.hpp"

using namespace penink;

TEST(ProgressBar, ModesOfAStagedStep) {
    auto run = [](ProgressMode mode) {
        std::ostringstream out;
        StageProgress p(out, mode, "building");
        for (int i = 0; i <= 20; ++i) p.update(i < 10 ? "reading" : "writing", i / 20.0);
        return out.str();
    };
    EXPECT_EQ(run(ProgressMode::off), "");
    const std::string lines = run(ProgressMode::lines);
    EXPECT_EQ(lines.find('\r'), std::string::npos);
    EXPECT_EQ(lines.rfind("penink: building: reading 0%\n", 0), 0u);
    EXPECT_NE(lines.find("penink: building: writing 50%\n"), std::string::npos);
    EXPECT_NE(lines.find("penink: building: writing 100%\n"), std::string::npos);
    EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 11);  // tenths 0..10, one line each
    const std::string tty = run(ProgressMode::terminal);
    EXPECT_EQ(std::count(tty.begin(), tty.end(), '\r'), 21);
    EXPECT_EQ(std::count(tty.begin(), tty.end(), '\n'), 1);  // ended at 100 %
    EXPECT_EQ(progress_mode(true, true), ProgressMode::off);
}

TEST(ProgressBar, OffModeDrawsNoSteps) {
    std::ostringstream out;
    ProgressBar bar(out, ProgressMode::off, "batch", 3);
    bar.step("frame_0001", 10.0);
    bar.finish();
    EXPECT_EQ(out.str(), "");
    ProgressBar lines(out, ProgressMode::lines, "batch", 3);
    lines.step("frame_0001", 10.0);
    EXPECT_EQ(out.str(), "penink: batch: 1/3 frame_0001 10 ms\n");
}
