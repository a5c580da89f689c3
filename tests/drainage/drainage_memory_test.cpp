#include "drainage/drainage_memory.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace penink {
namespace {

TEST(DrainageMemory, PointsOfAResampledGridDoNotWrap) {
    EXPECT_EQ(drainage_points(61, 87, 1), 61.0 * 87.0);
    EXPECT_EQ(drainage_points(61, 87, 5), 301.0 * 431.0);
    EXPECT_EQ(drainage_points(61, 87, 1000), 60001.0 * 86001.0);
    EXPECT_GT(drainage_points(2000000000, 2000000000, 1000), 1e24);
}

TEST(DrainageMemory, FactorIsTheGivenOneElseTheAutomaticOne) {
    EXPECT_EQ(drainage_factor_for(61, 87, 7), 7);
    EXPECT_EQ(drainage_factor_for(61, 87, 0), 5);
    EXPECT_EQ(drainage_factor_for(4001, 4001, 0), 1);  // 16 M points at factor 1: never below it
}

TEST(DrainageMemory, ResampleFactorBeyondTheBudgetIsRefused) {
    EXPECT_NO_THROW(check_drainage_memory("drainage", "v.asc", 61, 87, 5, std::uint64_t(1) << 30));
    try {
        check_drainage_memory("drainage", "v.asc", 61, 87, 1000, std::uint64_t(16) << 30);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "penink: drainage: v.asc: the drainage grid at factor 1000 (60001x86001 points) would need about "
                  "307.6 GiB of memory, 16.0 GiB available (--max-memory)");
    }
}

// At factor 1 the check counts the builds' measured line (penink drainage on jacksboro refined 10
// and 29 times: 571 MB and 2962 MB at peak) with a quarter more a point: above both measurements
// and above the cold render of x29 whole (3.25 GB at peak, its frame included: /usr/bin/time),
// under 1.25 times the larger build's (64 B a point counted 7.5 GB for a 4.0 GB build); at
// factor > 1, 64 B a point.
TEST(DrainageMemory, FactorOneCountsTheMeasuredPeakWithAMargin) {
    const double x10 = drainage_build_bytes(4030, 3440, 1), x29 = drainage_build_bytes(11687, 9976, 1);
    EXPECT_GT(x10, 571e6);
    EXPECT_GT(x29, 3255e6);
    EXPECT_LT(x29, 1.25 * 2962e6);
    EXPECT_DOUBLE_EQ(x29, drainage_peak_base_bytes + 1.25 * drainage_peak_bytes_per_point * 11687.0 * 9976.0);
    EXPECT_DOUBLE_EQ(drainage_build_bytes(61, 87, 5), 64.0 * 301.0 * 431.0);
}

}  // namespace
}  // namespace penink
