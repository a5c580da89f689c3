// each_where: the indices where the predicate holds, in order, across 64-index blocks and a short
// last block.
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

}  // namespace
}  // namespace penink
