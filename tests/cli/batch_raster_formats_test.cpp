// `penink batch --formats` takes the raster formats render writes: two frames as TIFF and JPEG
// (checked by their magic numbers and sizes read back by OpenImageIO), and an unknown format is
// one line listing the known ones.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";
const std::string path_csv = "position,elevation,azimuth,altitude,light_azimuth,light_altitude,min_score\n"
                             "\"1756568 5916728\",400,45,-20,300,40,\n"
                             "\"1756409 5916935\",400,60,-20,,,\n";

std::string size_of(const std::filesystem::path& p) {
    auto in = OIIO::ImageInput::open(p.string());
    if (!in) return "unreadable";
    return std::string(in->format_name()) + " " + std::to_string(in->spec().width) + "x" +
           std::to_string(in->spec().height);
}

}  // namespace

TEST(BatchRasterFormats, TiffAndJpegFrames) {
    const auto dir = fresh_dir("batch_raster");
    write_text(dir / "path.csv", path_csv);
    const RunResult r = run_penink("batch " + volcano + " --path path.csv --out frames --width 120 --height 90 "
                                   "--formats tif,jpg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* f : {"frame_0001", "frame_0002"}) {
        EXPECT_EQ(size_of(dir / "frames" / (std::string(f) + ".tif")), "tiff 120x90");
        EXPECT_EQ(size_of(dir / "frames" / (std::string(f) + ".jpg")), "jpeg 120x90");
    }
    EXPECT_EQ(file_count(dir / "frames"), 6u);  // 4 frames + timings.csv + timings.md
}

TEST(BatchRasterFormats, UnknownFormat) {
    const auto dir = fresh_dir("batch_raster_bad");
    write_text(dir / "path.csv", path_csv);
    const RunResult r = run_penink("batch " + volcano + " --path path.csv --out frames --formats svg,gif", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: cli: --formats: unknown format \"gif\" (use svg, ps, eps, pdf, png, tif, tiff, jpg, "
                        "jpeg, webp, exr)\n");
    EXPECT_FALSE(std::filesystem::exists(dir / "frames"));
}
