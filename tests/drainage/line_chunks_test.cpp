#include "drainage/line_chunks.hpp"

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace penink {
namespace {

// Lines of very different lengths (one long stem among many short ones): every line of the range
// reaches f exactly once, in ranges that follow one another, and no chunk's lines hold much more
// than its share of the vertices plus one line.
TEST(LineChunks, EachLineOnceInConsecutiveRangesOfEqualShares) {
    std::vector<DrapedLine> lines;
    std::uint32_t at = 0;
    for (int i = 0; i < 5000; ++i) {
        const std::uint32_t n = i == 1234 ? 40000 : 1 + std::uint32_t(i % 7);
        DrapedLine l;
        l.first = at, l.count = n, at += n;
        lines.push_back(l);
    }
    EXPECT_EQ(line_at(lines, 0), 0u);
    EXPECT_EQ(line_at(lines, 1), 1u);
    EXPECT_EQ(line_at(lines, at), lines.size());
    for (auto [l0, l1] : {std::pair<std::size_t, std::size_t>{0, 5000}, {100, 1300}, {1234, 1235}, {7, 7}}) {
        std::mutex m;
        std::vector<std::pair<std::size_t, std::size_t>> ranges;
        parallel_line_chunks(lines, at, l0, l1, 16, [&](std::size_t i0, std::size_t i1) {
            std::lock_guard<std::mutex> lock(m);
            ranges.push_back({i0, i1});
        });
        std::sort(ranges.begin(), ranges.end());
        std::size_t next = l0;
        for (auto [i0, i1] : ranges) {
            EXPECT_EQ(i0, next);
            EXPECT_LE(i0, i1);
            next = i1;
        }
        EXPECT_EQ(next, l1);
        if (l0 == l1) EXPECT_TRUE(ranges.empty());
    }
}

// Lines out of vertex order still reach f once each, in consecutive ranges.
TEST(LineChunks, LinesOutOfOrderEachOnce) {
    std::vector<DrapedLine> lines(3000);
    for (std::size_t i = 0; i < lines.size(); ++i) lines[i].first = std::uint32_t(3 * (lines.size() - 1 - i)), lines[i].count = 3;
    std::mutex m;
    std::vector<std::pair<std::size_t, std::size_t>> ranges;
    parallel_line_chunks(lines, 3 * lines.size(), 10, 2990, 16, [&](std::size_t i0, std::size_t i1) {
        std::lock_guard<std::mutex> lock(m);
        ranges.push_back({i0, i1});
    });
    std::sort(ranges.begin(), ranges.end());
    std::size_t next = 10;
    for (auto [i0, i1] : ranges) {
        EXPECT_EQ(i0, next);
        next = i1;
    }
    EXPECT_EQ(next, 2990u);
}

}  // namespace
}  // namespace penink
