// What the fills and accumulations by bands share (tiled_fill.hpp, tiled_accumulation.hpp):
// messages of plain values between ranks, a reader called one band at a time, and a pass over
// a list of bands on several threads. Internal to src/drainage.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <exception>
#include <future>
#include <mutex>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/parallel_chunks.hpp"
#include "core/ranks.hpp"

namespace penink::bands {

// Plain values appended in order: a message between ranks.
struct Writer {
    std::vector<std::uint8_t> out;
    template <class T> void put(const T& v) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
        out.insert(out.end(), p, p + sizeof v);
    }
    template <class T> void put_all(const std::vector<T>& v) {
        put(std::uint64_t(v.size()));
        const auto* p = reinterpret_cast<const std::uint8_t*>(v.data());
        out.insert(out.end(), p, p + v.size() * sizeof(T));
    }
};

// A Writer's values read back; a message cut short, or whose vector is not of the length
// expected (any, with the default), throws std::runtime_error.
struct Reader {
    std::span<const std::uint8_t> in;
    std::size_t at = 0;
    template <class T> T get() {
        if (in.size() - at < sizeof(T)) throw std::runtime_error("bands: a message cut short");
        T v;
        std::memcpy(&v, in.data() + at, sizeof v);
        at += sizeof v;
        return v;
    }
    template <class T> std::vector<T> get_all(std::size_t expected = ~std::size_t(0)) {
        const auto n = get<std::uint64_t>();
        if ((expected != ~std::size_t(0) && n != expected) || n > (in.size() - at) / sizeof(T))
            throw std::runtime_error("bands: a message of another grid");
        std::vector<T> v(static_cast<std::size_t>(n));
        std::memcpy(v.data(), in.data() + at, std::size_t(n) * sizeof(T));
        at += std::size_t(n) * sizeof(T);
        return v;
    }
    void end() const {
        if (at != in.size()) throw std::runtime_error("bands: a message with bytes after it");
    }
};

// A reader's calls made one at a time (GDAL's handle is one thread's).
template <class Read> auto one_at_a_time(const Read& read, std::mutex& m) {
    return [&read, &m](auto... args) {
        const std::lock_guard<std::mutex> lock(m);
        read(args...);
    };
}

// make(band) for every band of `which` on up to `threads` threads, the results in the order of
// `which`; tell() after each (from the thread that made it). The first exception stops the bands
// not started and is rethrown.
template <class Result, class Make, class Tell>
std::vector<Result> each_band(const std::vector<int>& which, int threads, Make&& make, Tell&& tell) {
    std::vector<Result> out(which.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t k; (k = next++) < which.size();) out[k] = make(which[k]), tell();
    };
    std::vector<std::future<void>> others;
    for (int t = 1; t < std::min<int>(threads, int(which.size())); ++t) others.push_back(std::async(std::launch::async, work));
    std::exception_ptr first;
    try {
        work();
    } catch (...) {
        first = std::current_exception(), next = which.size();
    }
    for (auto& o : others) try {
            o.get();
        } catch (...) {
            if (!first) first = std::current_exception();
        }
    if (first) std::rethrow_exception(first);
    return out;
}

// survey(b, read) for the bands `which` on up to `threads` threads, the calls of `read` (a
// std::function) one at a time; tell() after each.
template <class Survey, class Read, class SurveyFn, class Tell>
std::vector<Survey> survey_list(const std::vector<int>& which, const Read& read, int threads, SurveyFn&& survey, Tell&& tell) {
    std::mutex reading;
    const Read serial = one_at_a_time(read, reading);
    return each_band<Survey>(which, std::max(threads, 1), [&](int b) { return survey(b, serial); }, tell);
}

// finish(b, read, out) for the bands `which` on up to `threads` threads (the reads one at a time),
// out.band set first; each handed to use() in the order of `which`.
template <class Finished, class Read, class FinishFn, class Use>
void finish_in_order(const std::vector<int>& which, const Read& read, int threads, FinishFn&& finish, Use&& use) {
    std::mutex reading;
    const Read serial = one_at_a_time(read, reading);
    ordered_parts<Finished>(
        which.size(), std::size_t(std::max(threads, 1)),
        [&](std::size_t k, Finished& out) {
            out.band = which[k];
            finish(out.band, serial, out);
        },
        use);
}

// Tags of the messages of a distributed pass over bands.
inline constexpr int survey_tag = 1, band_tag = 2;

// The messages of a pass over n bands spread over the ranks of a distributed run, band b on rank
// b % size (`mine`: this rank's, ascending). Every rank surveys its bands (survey(mine): a vector
// of surveys); the other ranks send theirs to rank 0 (encode_survey), which decodes them
// (decode_survey(bytes), rank after rank, band after band), solves them all (solve(surveys):
// bytes) and broadcasts what it solved. Every rank then finishes its bands (finish(mine, solved
// bytes, use): use(finished) for each in row order, finished.band its number); the other ranks
// send each to rank 0 (encode_finished), which hands every band, its own made meanwhile and the
// others' received between them (decode_finished(band, bytes)), to put() in row order.
template <class Survey, class SurveyFn, class EncodeSurvey, class DecodeSurvey, class Solve, class FinishFn,
          class EncodeFinished, class DecodeFinished, class Put>
void over_ranks(Ranks& ranks, int n, SurveyFn&& survey, EncodeSurvey&& encode_survey, DecodeSurvey&& decode_survey,
                Solve&& solve, FinishFn&& finish, EncodeFinished&& encode_finished, DecodeFinished&& decode_finished,
                Put&& put) {
    const int size = ranks.size(), me = ranks.rank();
    std::vector<int> mine;
    for (int b = me; b < n; b += size) mine.push_back(b);
    std::vector<Survey> surveys = survey(mine);
    std::vector<std::uint8_t> solved;
    if (me == 0) {
        for (int r = 1; r < size; ++r)
            for (int b = r; b < n; b += size) surveys.push_back(decode_survey(ranks.receive(r, survey_tag)));
        solved = solve(surveys);
    } else {
        for (const Survey& s : surveys) ranks.send(0, survey_tag, encode_survey(s));
    }
    surveys.clear(), surveys.shrink_to_fit();
    ranks.broadcast(0, solved);
    if (me != 0) {
        finish(mine, std::move(solved), [&](const auto& f) { ranks.send(0, band_tag, encode_finished(f)); });
        return;
    }
    int next = 0;
    const auto others_before = [&](int band) {
        for (; next < band; ++next) put(decode_finished(next, ranks.receive(next % size, band_tag)));
    };
    finish(mine, std::move(solved), [&](const auto& f) {
        others_before(f.band);
        put(f), ++next;
    });
    others_before(n);
}

}  // namespace penink::bands
