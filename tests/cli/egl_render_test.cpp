// The EGL path (`--gl egl`, the one a GPU machine uses) draws exactly what OSMesa draws when both
// run llvmpipe: byte-identical SVG for the same scene and seed.
#include <filesystem>

#include <gtest/gtest.h>

#include "cli_support.hpp"

using namespace penink::test;

TEST(EglRender, SameSvgAsOsMesa) {
    const auto dir = fresh_dir("egl");
    std::filesystem::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    std::filesystem::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "volcano.prj");
    const std::string args = "render volcano.asc --width 240 --height 180 --style field-sketch ";
    const RunResult a = run_penink(args + "-o osmesa.svg --gl osmesa", dir);
    const RunResult b = run_penink(args + "-o egl.svg --gl egl", dir);
    ASSERT_EQ(a.code, 0) << a.output;
    ASSERT_EQ(b.code, 0) << b.output;
    const std::string osmesa = read_text(dir / "osmesa.svg"), egl = read_text(dir / "egl.svg");
    EXPECT_GT(osmesa.size(), 2000u);
    EXPECT_NE(osmesa.find("data-kind=\"crease\""), std::string::npos);
    EXPECT_EQ(osmesa, egl);
    std::filesystem::remove_all(dir);
}
