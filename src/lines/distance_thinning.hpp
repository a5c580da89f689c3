// Thinning by distance: a deterministic keep/drop decision per stroke whose keep probability
// falls linearly from 1 at eye distance `near` to `keep_far` at `far` (metres / world units),
// drawn from splitmix64 on (seed, id) so the result is independent of processing order.
#pragma once
#include <cstdint>

namespace penink {

// Keep probability: 1 for depth <= near, keep_far (clamped to [0, 1]) for depth >= far or a
// non-finite depth, linear in between; far <= near is a step at near.
double keep_probability(float depth, float near, float far, float keep_far);

// True when the stroke is kept: random_unit(seed, id, k) < keep_probability(...).
bool keep_stroke(float depth, float near, float far, float keep_far, std::uint64_t seed, std::uint64_t id);

}  // namespace penink
