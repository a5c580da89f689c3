// `penink render` restarts itself with its heap in transparent huge pages (core/huge_page_malloc.hpp)
// where the kernel gives them: `-v` says so, the tunables already set are kept, PENINK_HUGE_PAGES=0
// runs it as it is; the SVG is byte for byte the same either way.
#include <gtest/gtest.h>

#include <string>

#include "cli_support.hpp"
#include "core/huge_page_malloc.hpp"

using namespace penink::test;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";
const std::string said = "heap in transparent huge pages";

}  // namespace

TEST(HugePageMalloc, RenderRestartsInHugePagesWithTheSameDrawing) {
    const auto dir = fresh_dir("huge_page_malloc");
    const std::string args = "render '" + volcano + "' --width 320 --height 240 --cache-dir c -v -o ";
    const auto with = [&](const std::string& env, const std::string& out) {
        return run_penink("", dir, "env -u GLIBC_TUNABLES " + env + " '" PENINK_BINARY_PATH "' " + args + out);
    };
    const RunResult plain = with("PENINK_HUGE_PAGES=0", "plain.svg");
    ASSERT_EQ(plain.code, 0) << plain.output;
    EXPECT_EQ(plain.output.find(said), std::string::npos) << plain.output;
    const RunResult huge = with("", "huge.svg");
    ASSERT_EQ(huge.code, 0) << huge.output;
    EXPECT_EQ(huge.output.find(said) != std::string::npos, penink::kernel_gives_huge_pages()) << huge.output;
    const RunResult kept = with("GLIBC_TUNABLES=glibc.malloc.check=0", "kept.svg");
    ASSERT_EQ(kept.code, 0) << kept.output;
    EXPECT_EQ(kept.output.find(said) != std::string::npos, penink::kernel_gives_huge_pages()) << kept.output;
    const RunResult by_hand = with("GLIBC_TUNABLES=glibc.malloc.hugetlb=1 PENINK_HUGE_PAGES=0", "by_hand.svg");
    ASSERT_EQ(by_hand.code, 0) << by_hand.output;
    EXPECT_NE(by_hand.output.find(said), std::string::npos) << by_hand.output;
    const std::string svg = read_text(dir / "plain.svg");
    ASSERT_GT(svg.size(), 1000u);
    EXPECT_EQ(read_text(dir / "huge.svg"), svg);
    EXPECT_EQ(read_text(dir / "kept.svg"), svg);
    EXPECT_EQ(read_text(dir / "by_hand.svg"), svg);
}
