// Portable seeded random numbers for the lines stage: splitmix64 (Steele, Lea & Flood 2014)
// hashed over (seed, id, k) so every value depends only on those three integers, never on the
// order of processing nor on the standard library; unit values are in [0, 1).
#pragma once
#include <cstdint>
#include <cstring>

namespace penink {

inline std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// Random 64 bits for draw number k of object id under a seed.
inline std::uint64_t random_bits(std::uint64_t seed, std::uint64_t id, std::uint64_t k) {
    return splitmix64(splitmix64(splitmix64(seed) ^ id) ^ k);
}

// Uniform double in [0, 1) from the top 53 bits.
inline double unit_double(std::uint64_t bits) {
    return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

inline double random_unit(std::uint64_t seed, std::uint64_t id, std::uint64_t k) {
    return unit_double(random_bits(seed, id, k));
}

// A float's bit pattern, for hashing geometry into ids.
inline std::uint64_t float_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return std::uint64_t(u);
}

}  // namespace penink
