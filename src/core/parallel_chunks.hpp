// Runs f(begin, end) over consecutive chunks of [0, n) on up to hardware_concurrency threads (the
// calling one included): one chunk when n is below `min_chunk`. For loops over grid rows whose
// iterations write disjoint data; f must not depend on the chunking. The first exception thrown
// by a chunk is rethrown after all have finished.
#pragma once
#include <algorithm>
#include <cstddef>
#include <exception>
#include <future>
#include <thread>
#include <vector>

namespace penink {

template <class F> void parallel_chunks(std::size_t n, std::size_t min_chunk, F&& f) {
    const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    const std::size_t chunks = std::clamp<std::size_t>(n / std::max<std::size_t>(min_chunk, 1), 1, threads);
    const std::size_t per = (n + chunks - 1) / chunks;
    std::vector<std::future<void>> rest;
    for (std::size_t b = per; b < n; b += per)
        rest.push_back(std::async(std::launch::async, [&f, b, e = std::min(n, b + per)] { f(b, e); }));
    std::exception_ptr first;
    try {
        f(std::size_t(0), std::min(n, per));
    } catch (...) {
        first = std::current_exception();
    }
    for (auto& r : rest) {
        try {
            r.get();
        } catch (...) {
            if (!first) first = std::current_exception();
        }
    }
    if (first) std::rethrow_exception(first);
}

}  // namespace penink
