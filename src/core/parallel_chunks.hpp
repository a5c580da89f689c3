// Runs f(begin, end) over consecutive chunks of [0, n) on up to hardware_concurrency threads (the
// calling one included): one chunk when n is below `min_chunk`. For loops over grid rows whose
// iterations write disjoint data; f must not depend on the chunking. The first exception thrown
// by a chunk is rethrown after all have finished. parallel_collect: each chunk appends to its own
// vector, joined in chunk order (what one pass over [0, n) appends). run_beside: two jobs at once.
// ordered_parts: parts made in parallel, used in order (a stream encoded on all cores).
#pragma once
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <future>
#include <iterator>
#include <mutex>
#include <thread>
#include <vector>

namespace penink {

// The threads the loops here run on: hardware_concurrency, 1 to 16. Asked once a process and
// kept (a constant of the machine): glibc reads /sys/devices/system/cpu/online at every call, which
// a frame of a large DEM made 5 000 times (strace), one file opened, read and closed each.
inline std::size_t core_count() {
    static const std::size_t n = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    return n;
}

// Chunk length for n items: n split over up to core_count() chunks of >= min_chunk.
inline std::size_t chunk_length(std::size_t n, std::size_t min_chunk) {
    const std::size_t threads = core_count();
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
    if (n == 0) return {};  // no chunk, no part to collect into
    const std::size_t per = chunk_length(n, min_chunk);
    std::vector<std::vector<T>> parts((n + per - 1) / per);
    parallel_chunks(n, min_chunk, [&](std::size_t b, std::size_t e) { f(b, e, parts[b / per]); });
    std::vector<T> all;
    std::size_t total = 0;
    for (const auto& p : parts) total += p.size();
    all.reserve(total);
    for (auto& p : parts) all.insert(all.end(), std::make_move_iterator(p.begin()), std::make_move_iterator(p.end()));
    return all;
}

// Makes parts 0..n-1 on up to hardware_concurrency threads, make(p, out) filling `out` (a buffer
// reused from part to part: clear it first), and hands them to use(out) on the calling thread in
// order 0, 1, ..., n-1, with at most `ahead` parts made and not yet used (the memory it holds).
// The first exception (from make or use) stops the parts not yet started and is rethrown once
// every thread has stopped.
template <class Buffer, class Make, class Use>
void ordered_parts(std::size_t n, std::size_t ahead, Make&& make, Use&& use) {
    ahead = std::max<std::size_t>(ahead, 1);
    struct Slot {
        Buffer out;
        bool ready = false;
    };
    std::vector<Slot> slot(std::min(ahead, std::max<std::size_t>(n, 1)));
    std::mutex m;
    std::condition_variable cv;
    std::size_t used = 0, next = 0;  // parts used / handed to a maker so far
    std::exception_ptr error;
    auto fail = [&] {  // from a catch block: the first error kept, every waiting thread woken
        const std::lock_guard<std::mutex> lock(m);
        if (!error) error = std::current_exception();
        cv.notify_all();
    };
    auto maker = [&] {
        for (;;) {
            std::size_t p;
            {
                std::unique_lock<std::mutex> lock(m);
                cv.wait(lock, [&] { return error || next >= n || next < used + slot.size(); });
                if (error || next >= n) return;
                p = next++;
            }
            Slot& s = slot[p % slot.size()];
            try {
                make(p, s.out);
            } catch (...) {
                return fail();
            }
            const std::lock_guard<std::mutex> lock(m);
            s.ready = true;
            cv.notify_all();
        }
    };
    const std::size_t threads = core_count();
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < std::min(threads, n); ++t) pool.emplace_back(maker);
    for (; used < n;) {
        Slot& s = slot[used % slot.size()];
        {
            std::unique_lock<std::mutex> lock(m);
            cv.wait(lock, [&] { return error || s.ready; });
            if (error) break;
        }
        try {
            use(static_cast<const Buffer&>(s.out));
        } catch (...) {
            fail();
            break;
        }
        const std::lock_guard<std::mutex> lock(m);
        s.ready = false, ++used;
        cv.notify_all();
    }
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace penink
