// core/big_allocator.hpp: blocks of 2 MiB and more start on a 2 MiB boundary, values initialised
// like std::allocator's; small blocks and shrinking work.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/big_allocator.hpp"

namespace penink {
namespace {

TEST(BigAllocator, LargeBlocksAreHugePageAligned) {
    std::vector<std::uint32_t, BigAllocator<std::uint32_t>> big(3 << 20, 7u);  // 12 MiB
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % big_block_bytes, 0u);
    EXPECT_EQ(big[0], 7u);
    EXPECT_EQ(big.back(), 7u);  // value-initialised like std::allocator
    std::vector<std::uint8_t, UninitAllocator<std::uint8_t>> small(1000);
    small[999] = 3;
    EXPECT_EQ(small[999], 3);
    big.resize(10), big.shrink_to_fit();  // back below 2 MiB: freed through the mapping's size
    EXPECT_EQ(big.size(), 10u);
}

}  // namespace
}  // namespace penink
