// A line set's lines split over all cores by their vertices instead of their number: a set's
// lines lie in order from vertex 0 (line_set.hpp), so the line starting at or after a vertex
// index is found by bisection, and a chunk of vertices becomes the lines starting in it. One long
// stem then costs a chunk what many short ones do (the drainage stems' lengths span 1 to
// thousands of vertices).
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/parallel_chunks.hpp"
#include "drainage/line_set.hpp"

namespace penink {

// The first of `lines` (in order from vertex 0) whose first vertex is v or after; lines.size()
// when none is.
inline std::size_t line_at(const std::vector<DrapedLine>& lines, std::size_t v) {
    return std::size_t(std::partition_point(lines.begin(), lines.end(), [&](const DrapedLine& l) { return l.first < v; }) -
                       lines.begin());
}

// Calls f(i0, i1) for consecutive ranges of lines [l0, l1) (of `lines`, holding nv vertices in
// all) on up to hardware_concurrency threads: parallel_chunks over the vertices of those lines
// (chunks of at least min_vertices), each chunk the lines starting in it (possibly none). Lines
// out of vertex order (no set the builder makes) are split by their number instead.
template <class F>
void parallel_line_chunks(const std::vector<DrapedLine>& lines, std::size_t nv, std::size_t l0, std::size_t l1,
                          std::size_t min_vertices, F&& f) {
    if (l0 >= l1) return;
    const auto by_first = [](const DrapedLine& a, const DrapedLine& b) { return a.first < b.first; };
    if (!std::is_sorted(lines.begin(), lines.end(), by_first)) {
        parallel_chunks(l1 - l0, 1024, [&](std::size_t i0, std::size_t i1) { f(l0 + i0, l0 + i1); });
        return;
    }
    const auto first_of = [&](std::size_t l) { return l < lines.size() ? std::size_t(lines[l].first) : nv; };
    const std::size_t v0 = first_of(l0), v1 = first_of(l1);
    parallel_chunks(v1 - v0, min_vertices, [&](std::size_t c0, std::size_t c1) {
        const std::size_t i0 = c0 == 0 ? l0 : line_at(lines, v0 + c0), i1 = c1 == v1 - v0 ? l1 : line_at(lines, v0 + c1);
        f(i0, std::max(i0, i1));
    });
}

}  // namespace penink
