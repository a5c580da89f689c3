// each_where: the indices where the predicate holds, in order, across 64-index blocks and a short
// last block.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/bit_blocks.hpp"

namespace penink {
namespace {

TEST(BitBlocks, EachWhereVisitsTheIndicesThePredicateHoldsAtInOrder) {
    std::vector<int> seen;
    each_where(3, 203, [](int i) { return i % 7 == 0 || i == 66 || i == 67 || i == 202; }, [&](int i) { seen.push_back(i); });
    std::vector<int> want;
    for (int i = 3; i < 203; ++i)
        if (i % 7 == 0 || i == 66 || i == 67 || i == 202) want.push_back(i);
    EXPECT_EQ(seen, want);
    EXPECT_EQ(seen.front(), 7);
    EXPECT_EQ(seen.back(), 202);
    seen.clear();
    each_where(5, 5, [](int) { return true; }, [&](int i) { seen.push_back(i); });
    EXPECT_TRUE(seen.empty());
}

TEST(BitBlocks, SetFlagAtBitsOrsTheFlagIntoTheBytesOfTheSetBits) {
    std::vector<std::uint64_t> words(3, 0);
    words[0] = 1u | (std::uint64_t(1) << 63), words[2] = std::uint64_t(1) << 5;
    std::vector<std::uint8_t> bytes(192, 2);
    set_flag_at_bits(words, bytes.data(), 32);
    for (std::size_t i = 0; i < bytes.size(); ++i)
        EXPECT_EQ(bytes[i], i == 0 || i == 63 || i == 133 ? 34 : 2) << i;
}

}  // namespace
}  // namespace penink
