// Scans of index ranges where most indices need no work: a predicate decided for 64 indices at a
// time into a bit mask (a loop without branches, which the compiler can vectorise), then the work
// done only at the set bits, in index order; and per-index flag bytes set from a bit array.
#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/parallel_chunks.hpp"

namespace penink {

// f(i) for every i in [begin, end) where pred(i) holds, in increasing i.
template <class Pred, class F> void each_where(int begin, int end, Pred&& pred, F&& f) {
    for (int i0 = begin; i0 < end; i0 += 64) {
        const int n = std::min(64, end - i0);
        std::uint64_t mask = 0;
        for (int q = 0; q < n; ++q) mask |= std::uint64_t(pred(i0 + q)) << q;
        for (; mask; mask &= mask - 1) f(i0 + std::countr_zero(mask));
    }
}

// bytes[i] |= flag for every bit i set in `words` (bit i of words[i / 64]); words in parallel
// chunks, each byte written by one thread.
inline void set_flag_at_bits(const std::vector<std::uint64_t>& words, std::uint8_t* bytes, std::uint8_t flag) {
    parallel_chunks(words.size(), std::size_t(1) << 12, [&](std::size_t w0, std::size_t w1) {
        for (std::size_t w = w0; w < w1; ++w)
            for (std::uint64_t b = words[w]; b; b &= b - 1) bytes[w * 64 + std::size_t(std::countr_zero(b))] |= flag;
    });
}

}  // namespace penink
