// U32Map (core/u32_map.hpp) against std::unordered_map on a million seeded random inserts and
// lookups, keys drawn from a small range (many repeats, the first value kept) and the largest
// keys (0xffffffff included); it stays at most half full and grows from empty.
#include <cstdint>
#include <random>
#include <unordered_map>

#include <gtest/gtest.h>

#include "core/u32_map.hpp"

namespace penink {
namespace {

TEST(U32Map, AgreesWithUnorderedMap) {
    std::mt19937 rng(7);
    for (const std::uint32_t range : {1000u, 300000u, 0xffffffffu}) {
        U32Map map;
        std::unordered_map<std::uint32_t, std::uint32_t> want;
        for (int k = 0; k < 1000000; ++k) {
            const std::uint32_t key = range == 0xffffffffu && k % 7 == 0 ? 0xffffffffu - std::uint32_t(k % 3)
                                                                         : std::uint32_t(rng() % range);
            const std::uint32_t value = rng();
            ASSERT_EQ(map.insert(key, value), want.emplace(key, value).second) << range << " " << k;
            const std::uint32_t probe = std::uint32_t(rng() % range);
            const std::uint32_t* got = map.find(probe);
            const auto it = want.find(probe);
            ASSERT_EQ(got != nullptr, it != want.end()) << range << " " << k;
            if (got) ASSERT_EQ(*got, it->second);
        }
        EXPECT_EQ(map.size(), want.size()) << range;
        for (const auto& [key, value] : want) ASSERT_EQ(*map.find(key), value);
    }
}

}  // namespace
}  // namespace penink
