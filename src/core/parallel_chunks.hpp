// Runs f(begin, end) over consecutive chunks of [0, n) on up to hardware_concurrency threads (the
// calling one included): one chunk when n is below `min_chunk`. For loops over grid rows whose
// iterations write disjoint data; f must not depend on the chunking. The first exception thrown
// by a chunk is rethrown after all have finished. parallel_collect: each chunk appends to its own
// vector, joined in chunk order (what one pass over [0, n) appends). run_beside: two jobs at once.
#pragma once
#include <algorithm>
#include <cstddef>
#include <exception>
#include <future>
#include <thread>
#include <vector>

namespace penink {

// Chunk length for n items: n split over up to hardware_concurrency chunks of >= min_chunk.
inline std::size_t chunk_length(std::size_t n, std::size_t min_chunk) {
    const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    const std::size_t chunks = std::clamp<std::size_t>(n / std::max<std::size_t>(min_chunk, 1), 1, threads);
    return std::max<std::size_t>((n + chunks - 1) / chunks, 1);
}

template <class F> void parallel_chunks(std::size_t n, std::size_t min_chunk, F&& f) {
    const std::size_t per = chunk_length(n, min_chunk);
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

// Runs `beside` on a second thread while `here` runs on this one; returns when both are done and
// then rethrows the exception either threw (here's first).
template <class Beside, class Here> void run_beside(Beside&& beside, Here&& here) {
    std::exception_ptr beside_error;
    std::thread t([&] {
        try {
            beside();
        } catch (...) {
            beside_error = std::current_exception();
        }
    });
    try {
        here();
    } catch (...) {
        t.join();
        throw;
    }
    t.join();
    if (beside_error) std::rethrow_exception(beside_error);
}

// f(begin, end, out) appends to `out`, its chunk's own vector.
template <class T, class F> std::vector<T> parallel_collect(std::size_t n, std::size_t min_chunk, F&& f) {
    const std::size_t per = chunk_length(n, min_chunk);
    std::vector<std::vector<T>> parts((n + per - 1) / per);
    parallel_chunks(n, min_chunk, [&](std::size_t b, std::size_t e) { f(b, e, parts[b / per]); });
    std::vector<T> all;
    for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    return all;
}

}  // namespace penink
