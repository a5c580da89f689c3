// Wall-clock milliseconds for the per-pass and per-step timings printed by --verbose, batch
// and bench (std::chrono::steady_clock).
#pragma once
#include <chrono>

namespace penink {

using Clock = std::chrono::steady_clock;

// Milliseconds from t0 to now.
inline double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Milliseconds from t0 to now, and t0 moved to now: consecutive steps timed one after another.
inline double lap_ms(Clock::time_point& t0) {
    const Clock::time_point t1 = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    t0 = t1;
    return ms;
}

}  // namespace penink
