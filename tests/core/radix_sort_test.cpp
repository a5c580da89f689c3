// radix_sort_pairs orders pairs by (key, value) like std::sort on the pairs, whatever the keys'
// spread: few distinct keys (long equal runs sorted by value), keys differing only in low or only
// in high bytes, short ranges.
#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/radix_sort.hpp"

namespace penink {
namespace {

// Sorts n pairs with keys from `key(rng)` both ways and compares.
template <class Key> void expect_sorted_like_std(std::size_t n, unsigned seed, Key&& key) {
    std::mt19937_64 rng(seed);
    std::vector<std::uint64_t> keys(n);
    std::vector<std::uint32_t> values(n);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> want(n);
    for (std::size_t i = 0; i < n; ++i) {
        keys[i] = key(rng), values[i] = std::uint32_t(rng());
        want[i] = {keys[i], values[i]};
    }
    std::sort(want.begin(), want.end());
    radix_sort_pairs(keys.data(), values.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(keys[i], want[i].first) << "at " << i << " of " << n;
        ASSERT_EQ(values[i], want[i].second) << "at " << i << " of " << n;
    }
}

TEST(RadixSort, OrdersPairsByKeyThenValue) {
    for (const std::size_t n : {0, 1, 2, 31, 32, 33, 1000, 100000}) {
        expect_sorted_like_std(n, 1, [](std::mt19937_64& r) { return r(); });
        expect_sorted_like_std(n, 2, [](std::mt19937_64& r) { return r() % 5; });  // long equal runs
        expect_sorted_like_std(n, 3, [](std::mt19937_64& r) { return (r() % 7) << 60; });  // high byte only
        expect_sorted_like_std(n, 4, [](std::mt19937_64& r) { return (r() % 300) << 24 | 0xabcd000000000000u; });
    }
}

}  // namespace
}  // namespace penink
