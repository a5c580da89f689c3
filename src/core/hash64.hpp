// A 64-bit checksum of bytes: FNV-1a over little-endian 64-bit words, the tail bytes one by one.
// Used by the cache files (drainage database, terrain cache) to detect damaged files; not a
// cryptographic hash.
#pragma once
#include <cstddef>
#include <cstdint>

namespace penink {

// Chained: hash64(b, m, hash64(a, n)) hashes a then b (when n is a multiple of 8).
std::uint64_t hash64(const void* data, std::size_t size, std::uint64_t seed = 0xcbf29ce484222325ull);

}  // namespace penink
