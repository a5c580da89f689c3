// core/parallel_chunks.hpp: every index visited once, chunk outputs joined in order, exceptions
// carried out of the other threads; ordered parts used in order.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel_chunks.hpp"

namespace penink {
namespace {

TEST(ParallelChunks, EveryIndexOnceAndCollectInOrder) {
    for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(100003)}) {
        std::vector<int> hits(n, 0);
        parallel_chunks(n, 10, [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) ++hits[i];
        });
        EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), std::size_t(0)), n);
        for (int h : hits) ASSERT_EQ(h, 1);
        const std::vector<std::size_t> odd = parallel_collect<std::size_t>(
            n, 10, [](std::size_t b, std::size_t e, std::vector<std::size_t>& out) {
                for (std::size_t i = b; i < e; ++i)
                    if (i % 2) out.push_back(i);
            });
        ASSERT_EQ(odd.size(), n / 2);
        for (std::size_t k = 0; k < odd.size(); ++k) ASSERT_EQ(odd[k], 2 * k + 1);
    }
}

TEST(ParallelChunks, ExceptionsComeOutOfEitherSide) {
    int ran = 0;
    EXPECT_THROW(run_beside([] { throw std::runtime_error("beside"); }, [&] { ++ran; }), std::runtime_error);
    EXPECT_EQ(ran, 1);  // the other job still ran to its end
    EXPECT_THROW(run_beside([&] { ++ran; }, [] { throw std::logic_error("here"); }), std::logic_error);
    EXPECT_EQ(ran, 2);
    EXPECT_THROW(parallel_chunks(1000, 1, [](std::size_t b, std::size_t) {
                     if (b > 0) throw std::runtime_error("chunk");
                 }),
                 std::runtime_error);
}

TEST(OrderedParts, UsedInOrderWithBoundedLookAhead) {
    for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(1000)}) {
        std::atomic<std::size_t> made{0}, used{0};
        std::size_t most_ahead = 0;
        std::vector<std::size_t> seen;
        ordered_parts<std::vector<std::size_t>>(
            n, 3,
            [&](std::size_t p, std::vector<std::size_t>& out) {
                out.assign(p % 7 + 1, p);  // parts of different lengths
                ++made;
            },
            [&](const std::vector<std::size_t>& out) {
                most_ahead = std::max(most_ahead, made.load() - used.load());
                ASSERT_EQ(out.size(), out.front() % 7 + 1);
                seen.push_back(out.front());
                ++used;
            });
        ASSERT_EQ(seen.size(), n);
        for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(seen[k], k);
        EXPECT_LE(most_ahead, 3u);  // never more than `ahead` parts made and waiting
    }
}

TEST(OrderedParts, AnExceptionStopsTheRestAndComesOut) {
    std::atomic<std::size_t> made{0};
    EXPECT_THROW(ordered_parts<std::vector<int>>(
                     100000, 2,
                     [&](std::size_t p, std::vector<int>&) {
                         ++made;
                         if (p == 10) throw std::runtime_error("make");
                     },
                     [](const std::vector<int>&) {}),
                 std::runtime_error);
    EXPECT_LT(made.load(), 100u);  // the parts after the failure were not started
    std::size_t used = 0;
    EXPECT_THROW(ordered_parts<std::vector<int>>(
                     1000, 2, [](std::size_t, std::vector<int>&) {},
                     [&](const std::vector<int>&) {
                         if (++used == 3) throw std::logic_error("use");
                     }),
                 std::logic_error);
    EXPECT_EQ(used, 3u);
}

}  // namespace
}  // namespace penink
