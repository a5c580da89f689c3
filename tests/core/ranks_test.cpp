// Ranks as threads (the protocol the MPI module carries): messages arrive in the order sent per
// sender and tag, a broadcast reaches every rank, and a rank that fails wakes the ranks waiting on
// it with an error instead of leaving them blocked.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include "core/ranks.hpp"

namespace penink {
namespace {

TEST(Ranks, ThreadRanksKeepOrderAndBroadcast) {
    std::atomic<int> checked{0};
    run_thread_ranks(4, [&](Ranks& r) {
        EXPECT_EQ(r.size(), 4);
        if (r.rank() != 0) {
            for (std::uint8_t k = 0; k < 5; ++k) r.send(0, 7, std::vector<std::uint8_t>{std::uint8_t(r.rank()), k});
        } else {
            for (int from = 1; from < 4; ++from)
                for (std::uint8_t k = 0; k < 5; ++k)
                    EXPECT_EQ(r.receive(from, 7), (std::vector<std::uint8_t>{std::uint8_t(from), k}));
        }
        std::vector<std::uint8_t> b;
        if (r.rank() == 2) b = {1, 2, 3};
        r.broadcast(2, b);
        EXPECT_EQ(b, (std::vector<std::uint8_t>{1, 2, 3}));
        ++checked;
    });
    EXPECT_EQ(checked, 4);
}

TEST(Ranks, AFailedRankWakesTheOthers) {
    EXPECT_THROW(run_thread_ranks(3,
                                  [](Ranks& r) {
                                      if (r.rank() == 1) throw std::runtime_error("rank 1 failed");
                                      r.receive(1, 0);  // would wait for ever
                                  }),
                 std::runtime_error);
    try {
        run_thread_ranks(2, [](Ranks& r) {
            if (r.rank() == 1) throw std::invalid_argument("the first error");
            r.receive(1, 0);
        });
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "the first error");
    }
}

}  // namespace
}  // namespace penink
