// The camera on the command line of `penink render` (--position, --elevation, --azimuth,
// --altitude, --fov, --target, --distance): the drawing's metadata records the camera used,
// and an option the scene's kind does not take is one line, exit 2, nothing written.
#include <gtest/gtest.h>

#include "cli_support.hpp"

using namespace penink::test;

namespace {
const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";
}

TEST(CameraOptionsCli, AzimuthAltitudeAndFovReachTheCamera) {
    const auto dir = fresh_dir("camera_angles");
    const RunResult r = run_penink("render " + volcano + " --azimuth 90 --altitude -20 --fov 30 --width 160 --height 120 "
                                                         "-o v.svg",
                                   dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "v.svg");
    EXPECT_NE(svg.find("azimuth 90, altitude -20, fov 30, 160x120"), std::string::npos) << svg.substr(0, 2000);
}

TEST(CameraOptionsCli, PositionAndTargetAimTheCamera) {
    const auto dir = fresh_dir("camera_target");
    // From 1757000 E 5917100 N at 400 m towards 1757300 E 5917500 N: bearing atan2(300, 400) = 36.87 degrees.
    const RunResult r = run_penink("render " + volcano + " --position '1757000 5917100' --elevation 400 "
                                                         "--target '1757300 5917500' --width 160 --height 120 -o v.svg",
                                   dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "v.svg");
    EXPECT_NE(svg.find("eye 1757000 5917100 "), std::string::npos);
    EXPECT_NE(svg.find("azimuth 36.86989765"), std::string::npos) << svg.substr(0, 2000);
}

TEST(CameraOptionsCli, TerrainOptionsOnAMeshSceneAreErrors) {
    const auto dir = fresh_dir("camera_mesh");
    for (const std::string option : {"--target '0 0'", "--position '0 0'", "--distance 5", "--elevation 3"}) {
        const RunResult r = run_penink("render " PENINK_SOURCE_DIR "/examples/house.toml " + option + " -o h.svg", dir);
        EXPECT_EQ(r.code, 2) << r.output;
        const std::string name = option.substr(0, option.find(' '));
        EXPECT_EQ(r.output, "penink: cli: " PENINK_SOURCE_DIR "/examples/house.toml: " + name +
                                " applies to terrain scenes only (a mesh's camera is set by [camera] eye, target and up)\n");
        EXPECT_EQ(file_count(dir), 0u);
    }
}

TEST(CameraOptionsCli, AnAzimuthBesidePositionAndTargetIsAnError) {
    const auto dir = fresh_dir("camera_conflict");
    const RunResult r = run_penink("render " + volcano + " --position '1757000 5917100' --elevation 400 "
                                                         "--target '1757300 5917500' --azimuth 10 -o v.svg",
                                   dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: " + volcano +
                            ": camera azimuth and altitude follow from position and target: give one or the other\n");
    EXPECT_EQ(file_count(dir), 0u);
}
