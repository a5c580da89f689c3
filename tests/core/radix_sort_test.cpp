// radix_sort_pairs orders pairs by (key, value) like std::sort on the pairs, whatever the keys'
// spread: few distinct keys (long equal runs sorted by value), keys differing only in low or only
// in high bytes, short ranges. radix_sort_bits orders words by a range of their bits like
// std::stable_sort comparing those bits, for ranges of one digit, several and all 64 bits.
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

// Sorts n words from `word(rng)` by bits [lo, hi) both ways and compares (stable: the bits
// outside the range tell words equal inside it apart).
template <class Word> void expect_bits_sorted_like_std(std::size_t n, unsigned seed, int lo, int hi, Word&& word) {
    std::mt19937_64 rng(seed);
    std::vector<std::uint64_t> words(n), scratch;
    for (std::uint64_t& w : words) w = word(rng);
    auto bits = [&](std::uint64_t w) { return hi - lo == 64 ? w : w >> lo & ((std::uint64_t(1) << (hi - lo)) - 1); };
    std::vector<std::uint64_t> want = words;
    std::stable_sort(want.begin(), want.end(), [&](std::uint64_t a, std::uint64_t b) { return bits(a) < bits(b); });
    radix_sort_bits(words, scratch, lo, hi);
    ASSERT_EQ(words, want) << n << " words, bits " << lo << ".." << hi;
}

TEST(RadixSort, OrdersWordsByBitRangeStably) {
    for (const std::size_t n : {0, 1, 2, 33, 1000, 100000}) {
        expect_bits_sorted_like_std(n, 1, 0, 64, [](std::mt19937_64& r) { return r(); });
        expect_bits_sorted_like_std(n, 2, 20, 26, [](std::mt19937_64& r) { return r(); });  // one digit
        expect_bits_sorted_like_std(n, 3, 35, 61, [](std::mt19937_64& r) { return r(); });  // three digits
        expect_bits_sorted_like_std(n, 4, 8, 40, [](std::mt19937_64& r) { return (r() % 3) << 20 | (r() & 0xff); });  // long equal runs
        expect_bits_sorted_like_std(n, 5, 4, 30, [](std::mt19937_64& r) { return r() & 0xf0000000ffffffffu; });  // a pass of one value
    }
}

}  // namespace
}  // namespace penink
