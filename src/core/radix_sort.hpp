// Sorts of unsigned integers.
// radix_sort_pairs: (key, value) pairs by (key, value), both unsigned, in place: most-significant-
// digit radix sort with the in-place permutation of American flag sort (McIlroy, Bostic &
// McIlroy 1993, "Engineering radix sort"), 8-bit digits; a run of equal keys sorted by value, a
// short range by insertion. No copy of the arrays: O(1) memory beyond a count per digit value per
// level, O(n * key bytes) time.
// radix_sort_bits: 64-bit words by a range of their bits, stable: least-significant-digit radix
// sort (Knuth, TAOCP vol. 3, 5.2.5) through a scratch array of the same length, digits of up to
// 11 bits (as few passes as the range needs; every pass's counts taken in one read first),
// O(n * passes) time.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace penink {

namespace radix_detail {

// Byte `shift / 8` of key k.
inline std::size_t digit(std::uint64_t k, int shift) { return std::size_t(k >> shift) & 0xff; }

template <class V> void insertion_sort(std::uint64_t* keys, V* values, std::size_t n) {
    for (std::size_t i = 1; i < n; ++i) {
        const std::uint64_t k = keys[i];
        const V v = values[i];
        std::size_t j = i;
        for (; j > 0 && (keys[j - 1] > k || (keys[j - 1] == k && values[j - 1] > v)); --j)
            keys[j] = keys[j - 1], values[j] = values[j - 1];
        keys[j] = k, values[j] = v;
    }
}

// keys[0, n) agree above bit shift + 8; sorts them by the bits from shift + 7 down, then value.
template <class V> void flag_sort(std::uint64_t* keys, V* values, std::size_t n, int shift) {
    if (n < 32) return insertion_sort(keys, values, n);
    if (shift < 0) return std::sort(values, values + n);  // equal keys
    std::array<std::size_t, 256> count{}, next{};
    for (std::size_t i = 0; i < n; ++i) ++count[digit(keys[i], shift)];
    if (count[digit(keys[0], shift)] == n) return flag_sort(keys, values, n, shift - 8);
    std::array<std::size_t, 257> start{};
    for (std::size_t b = 0; b < 256; ++b) start[b + 1] = start[b] + count[b];
    std::copy(start.begin(), start.end() - 1, next.begin());
    for (std::size_t b = 0; b < 256; ++b)  // cycle each misplaced pair to its bucket
        while (next[b] < start[b + 1]) {
            std::size_t d = digit(keys[next[b]], shift);
            while (d != b) {
                const std::size_t to = next[d]++;
                std::swap(keys[next[b]], keys[to]), std::swap(values[next[b]], values[to]);
                d = digit(keys[next[b]], shift);
            }
            ++next[b];
        }
    for (std::size_t b = 0; b < 256; ++b)
        if (count[b] > 1) flag_sort(keys + start[b], values + start[b], count[b], shift - 8);
}

}  // namespace radix_detail

// keys[i] and values[i] (n pairs) reordered together, ascending by key, equal keys by value.
template <class V> void radix_sort_pairs(std::uint64_t* keys, V* values, std::size_t n) {
    radix_detail::flag_sort(keys, values, n, 56);
}

// words reordered ascending by their bits [lo, hi) (0 <= lo <= hi <= 64), words equal in those bits
// in their order before; `scratch` resized to words.size() and left holding no meaning.
template <class A> void radix_sort_bits(std::vector<std::uint64_t, A>& words, std::vector<std::uint64_t, A>& scratch,
                                        int lo, int hi) {
    const int bits = hi - lo;
    if (bits <= 0 || words.size() < 2) return;
    const int passes = (bits + 10) / 11, width = (bits + passes - 1) / passes;
    const std::size_t buckets = std::size_t(1) << width, n = words.size();
    // pass p: the digit of bits [lo + p * width, min(hi, lo + (p + 1) * width))
    auto digit = [&](std::uint64_t w, int p) {
        const int shift = lo + p * width, used = std::min(width, hi - shift);
        return std::size_t(w >> shift & ((std::uint64_t(1) << used) - 1));
    };
    std::vector<std::size_t> count(std::size_t(passes) * buckets, 0);
    for (const std::uint64_t w : words)
        for (int p = 0; p < passes; ++p) ++count[std::size_t(p) * buckets + digit(w, p)];
    scratch.resize(n);
    for (int p = 0; p < passes; ++p) {
        std::size_t* start = count.data() + std::size_t(p) * buckets;
        if (start[digit(words[0], p)] == n) continue;  // one digit value: already in order
        std::size_t at = 0;
        for (std::size_t b = 0; b < buckets; ++b) at += std::exchange(start[b], at);
        for (const std::uint64_t w : words) scratch[start[digit(w, p)]++] = w;
        words.swap(scratch);
    }
}

}  // namespace penink
