// `penink drainage --routing`: least-cost reaches the database's fingerprint, priority-flood is
// the default, and a bad value is CLI11's one-line error with exit code 2 and no database.
#include <filesystem>

#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "drainage/drainage_db.hpp"

namespace penink {
namespace {

using namespace penink::test;
namespace fs = std::filesystem;

TEST(DrainageRoutingCli, RoutingOptionReachesTheFingerprint) {
    const fs::path dir = fresh_dir("routing");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    RunResult r = run_penink("drainage volcano.asc --resample 1 -q -o default.dv", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    r = run_penink("drainage volcano.asc --resample 1 -q --routing least-cost -o lc.dv", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    r = run_penink("drainage volcano.asc --resample 1 -q --routing priority-flood -o pf.dv", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(read_drainage_db((dir / "default.dv").string()).fingerprint.routing, 0u);
    EXPECT_EQ(read_drainage_db((dir / "pf.dv").string()).fingerprint.routing, 0u);
    EXPECT_EQ(read_drainage_db((dir / "lc.dv").string()).fingerprint.routing, 1u);

    r = run_penink("drainage volcano.asc --resample 1 --routing steepest -o bad.dv", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("--routing: steepest not in {priority-flood,least-cost}"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "bad.dv"));
    r = run_penink("drainage --help", dir);
    EXPECT_NE(r.output.find("--routing"), std::string::npos) << r.output;
    fs::remove_all(dir);
}

// A scene's [drainage] routing reaches the cache render builds; a bad name is one scene error.
TEST(DrainageRoutingCli, SceneRoutingReachesTheRenderCache) {
    const fs::path dir = fresh_dir("routing-scene");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    const std::string scene = "[terrain]\ndem = \"volcano.asc\"\n[camera]\nwidth = 160\nheight = 120\n";
    write_text(dir / "lc.toml", scene + "[drainage]\nrouting = \"least-cost\"\n");
    RunResult r = run_penink("render lc.toml -o lc.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(read_drainage_db((dir / "volcano.asc.dv").string()).fingerprint.routing, 1u);
    write_text(dir / "pf.toml", scene);  // default: the cache is stale and rebuilt
    r = run_penink("render pf.toml -o pf.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(read_drainage_db((dir / "volcano.asc.dv").string()).fingerprint.routing, 0u);

    write_text(dir / "bad.toml", scene + "[drainage]\nrouting = \"steepest\"\n");
    r = run_penink("render bad.toml -o bad.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: bad.toml: [drainage] routing must be \"priority-flood\" or "
                        "\"least-cost\" (got \"steepest\")\n");
    EXPECT_FALSE(fs::exists(dir / "bad.svg"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace penink
