#include "core/memory_budget.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace penink {
namespace {

TEST(MemoryBudget, ParsesSizesAsPeopleWriteThem) {
    EXPECT_EQ(parse_byte_size("2G"), std::uint64_t(2) << 30);
    EXPECT_EQ(parse_byte_size("2GiB"), std::uint64_t(2) << 30);
    EXPECT_EQ(parse_byte_size("2gb"), std::uint64_t(2) << 30);
    EXPECT_EQ(parse_byte_size("512M"), std::uint64_t(512) << 20);
    EXPECT_EQ(parse_byte_size("64k"), std::uint64_t(64) << 10);
    EXPECT_EQ(parse_byte_size("1.5G"), std::uint64_t(3) << 29);
    EXPECT_EQ(parse_byte_size("3000000"), std::uint64_t(3000000));
    EXPECT_EQ(parse_byte_size("1T"), std::uint64_t(1) << 40);
    for (const char* bad : {"", "G", "0", "-1G", "2X", "2 G", "inf", "nan", "1e300", "2GG"})
        EXPECT_FALSE(parse_byte_size(bad).has_value()) << bad;
}

TEST(MemoryBudget, FormatsBytes) {
    EXPECT_EQ(format_bytes(100), "100 B");
    EXPECT_EQ(format_bytes(512.0 * 1024 * 1024), "512 MiB");
    EXPECT_EQ(format_bytes(2.0 * 1024 * 1024 * 1024), "2.0 GiB");
    EXPECT_EQ(format_bytes(330e9), "307.3 GiB");
}

TEST(MemoryBudget, AvailableMemoryIsKnownHere) { EXPECT_GT(available_memory_bytes(), 0u); }

TEST(MemoryBudget, BudgetIsTheLimitGivenElseWhatIsAvailable) {
    EXPECT_EQ(memory_budget(12345), 12345u);
    EXPECT_GT(memory_budget(0), 0u);
}

TEST(MemoryBudget, CheckNamesWhatTheInputWouldNeed) {
    EXPECT_NO_THROW(check_memory("input", "a.asc", "x", 1000.0, 1000));
    EXPECT_NO_THROW(check_memory("input", "a.asc", "x", 1e30, 0));  // unknown budget: no limit
    try {
        check_memory("input", "a.asc", "reading the DEM's 50000x50000 nodes", 52.5e9, std::uint64_t(2) << 30);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "penink: input: a.asc: reading the DEM's 50000x50000 nodes would need about 48.9 GiB of memory, "
                  "2.0 GiB available (--max-memory)");
        EXPECT_EQ(e.code(), ExitCode::bad_input);
    }
}

}  // namespace
}  // namespace penink
