// The raster writer module penink_oiio.so (OpenImageIO) is loaded only when a raster is asked
// for: a vector-only render does not load OpenImageIO (seen through the dynamic loader's log),
// a raster render does; a penink binary without its module refuses a raster output with one
// line before drawing anything, and still writes vector files; a module that cannot be loaded
// is one line too, and no output is left.
#include <gtest/gtest.h>

#include <algorithm>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

namespace fs = std::filesystem;

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";

// How many times the dynamic loader's log of `penink args` names OpenImageIO's library.
int oiio_loads(const std::string& args, const fs::path& dir) {
    const RunResult r = run_penink("", dir, "LD_DEBUG=files LD_DEBUG_OUTPUT='" + (dir / "ld").string() + "' '" +
                                               PENINK_BINARY_PATH "' " + args);
    EXPECT_EQ(r.code, 0) << r.output;
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().filename().string().rfind("ld.", 0) != 0) continue;
        const std::string log = read_text(e.path());
        for (std::size_t at = log.find("file=libOpenImageIO.so"); at != std::string::npos;
             at = log.find("file=libOpenImageIO.so", at + 1))
            ++n;
        fs::remove(e.path());
    }
    return n;
}

}  // namespace

TEST(RasterModule, LoadedOnlyForRasters) {
    const auto dir = fresh_dir("raster_module_lazy");
    EXPECT_EQ(oiio_loads("render " + volcano + " --width 80 --height 60 -o a.svg -o a.pdf", dir), 0);
    EXPECT_GT(oiio_loads("render " + volcano + " --width 80 --height 60 -o b.svg -o b.tif", dir), 0);
    EXPECT_TRUE(fs::exists(dir / "a.svg"));
    EXPECT_TRUE(fs::exists(dir / "b.tif"));
}

TEST(RasterModule, MissingModuleIsOneLineBeforeDrawing) {
    const auto dir = fresh_dir("raster_module_missing");
    fs::create_directories(dir / "bin");
    fs::copy_file(PENINK_BINARY_PATH, dir / "bin" / "penink");
    const std::string bin = (dir / "bin" / "penink").string();
    const RunResult r = run_penink("", dir, "'" + bin + "' render " + volcano + " --width 80 --height 60 -o out.svg -o out.png");
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: export: out.png: cannot write raster images: penink_oiio.so (OpenImageIO) not found "
                        "(looked for " + (dir / "bin" / "penink_oiio.so").string() + ", " +
                        (dir / "lib" / "penink" / "penink_oiio.so").string() + ")\n");
    EXPECT_FALSE(fs::exists(dir / "out.svg"));
    EXPECT_EQ(file_count(dir), 0u);
    const RunResult v = run_penink("", dir, "'" + bin + "' render " + volcano + " --width 80 --height 60 -o out.svg");
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_TRUE(fs::exists(dir / "out.svg"));
}

TEST(RasterModule, UnloadableModuleIsOneLineAndNoOutput) {
    const auto dir = fresh_dir("raster_module_bad");
    fs::create_directories(dir / "bin");
    fs::copy_file(PENINK_BINARY_PATH, dir / "bin" / "penink");
    write_text(dir / "bin" / "penink_oiio.so", "not a shared library\n");
    const std::string bin = (dir / "bin" / "penink").string();
    const RunResult r = run_penink("", dir, "'" + bin + "' render " + volcano + " --width 80 --height 60 -o out.svg -o out.png");
    EXPECT_EQ(r.code, 2);
    const std::string start = "penink: export: out.png: cannot write raster images: cannot load " +
                              (dir / "bin" / "penink_oiio.so").string() + " (";
    EXPECT_EQ(r.output.substr(0, start.size()), start) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(file_count(dir), 0u);
}
