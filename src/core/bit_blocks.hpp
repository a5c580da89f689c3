// Scans of index ranges where most indices need no work: a predicate decided for 64 indices at a
// time into a bit mask (a loop without branches, which the compiler can vectorise), then the work
// done only at the set bits, in index order.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>

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

}  // namespace penink
