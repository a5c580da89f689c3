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

}  // namespace
}  // namespace penink
