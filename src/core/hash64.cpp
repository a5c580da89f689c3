#include "core/hash64.hpp"

#include <bit>
#include <cstring>

namespace penink {

static_assert(std::endian::native == std::endian::little, "hash64 reads words little-endian");

std::uint64_t hash64(const void* data, std::size_t size, std::uint64_t h) {
    constexpr std::uint64_t prime = 0x100000001b3ull;
    const auto* p = static_cast<const std::uint8_t*>(data);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        std::uint64_t w;
        std::memcpy(&w, p + i, 8);
        h = (h ^ w) * prime;
    }
    for (; i < size; ++i) h = (h ^ p[i]) * prime;
    return h;
}

}  // namespace penink
