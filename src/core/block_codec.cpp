#include "core/block_codec.hpp"

#include <bit>
#include <cstring>
#include <new>

#include <zlib.h>

namespace penink {

namespace {

// Deflate level 2 (zlib's fast matcher): on the node positions of jacksboro refined 10 times it
// codes 1.17 bytes a node, level 4 (the lazy matcher) 1.02 at up to twice the CPU (1.3 against
// 2.4 s measured on a loaded machine). A window of 2^12 bytes spans a block's planes (3 KiB for
// 256 nodes) and a hash of 2^12 entries (memory level 5) is cleared per block in a fraction of
// the default's 2^15; any inflater (window 2^15) reads the stream.
constexpr int deflate_level = 2, window_bits = 12, memory_level = 5;

std::uint32_t ordered(float v) {
    const std::uint32_t b = std::bit_cast<std::uint32_t>(v);
    return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
float unordered(std::uint32_t u) {
    return std::bit_cast<float>((u & 0x80000000u) ? (u & 0x7fffffffu) : ~u);
}
std::uint32_t zigzag(std::uint32_t d) { return (d << 1) ^ std::uint32_t(-std::int32_t(d >> 31)); }
std::uint32_t unzigzag(std::uint32_t z) { return (z >> 1) ^ std::uint32_t(-std::int32_t(z & 1)); }

std::vector<std::uint8_t> deflate_raw(const std::uint8_t* data, std::size_t n) {
    z_stream s{};
    if (deflateInit2(&s, deflate_level, Z_DEFLATED, -window_bits, memory_level, Z_DEFAULT_STRATEGY) != Z_OK) throw std::bad_alloc();
    std::vector<std::uint8_t> out(deflateBound(&s, uLong(n)));
    s.next_in = const_cast<Bytef*>(data), s.avail_in = uInt(n);
    s.next_out = out.data(), s.avail_out = uInt(out.size());
    const int r = deflate(&s, Z_FINISH);
    out.resize(out.size() - s.avail_out);
    deflateEnd(&s);
    if (r != Z_STREAM_END) throw std::bad_alloc();  // deflateBound guarantees room: only memory fails
    return out;
}

// Inflates exactly n bytes that end the stream; false otherwise.
bool inflate_raw(const std::uint8_t* coded, std::size_t size, std::uint8_t* out, std::size_t n) {
    z_stream s{};
    if (inflateInit2(&s, -15) != Z_OK) return false;
    s.next_in = const_cast<Bytef*>(coded), s.avail_in = uInt(size);
    s.next_out = out, s.avail_out = uInt(n);
    const int r = inflate(&s, Z_FINISH);
    const bool ok = r == Z_STREAM_END && s.avail_out == 0 && s.avail_in == 0;
    inflateEnd(&s);
    return ok;
}

}  // namespace

std::vector<std::uint8_t> encode_floats(const float* data, std::size_t n, std::span<const int> orders) {
    const int comps = int(orders.size());
    const std::size_t count = n * std::size_t(comps);
    std::vector<std::uint8_t> planes(count * 4);
    std::vector<std::uint32_t> u(n);
    for (int k = 0; k < comps; ++k) {
        for (std::size_t i = 0; i < n; ++i) u[i] = ordered(data[i * std::size_t(comps) + std::size_t(k)]);
        for (int o = 0; o < orders[std::size_t(k)]; ++o)
            for (std::size_t i = n; i-- > 1;) u[i] -= u[i - 1];
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t z = zigzag(u[i]);
            const std::size_t at = std::size_t(k) * n + i;
            for (std::size_t b = 0; b < 4; ++b) planes[b * count + at] = std::uint8_t(z >> (8 * b));
        }
    }
    return deflate_raw(planes.data(), planes.size());
}

bool decode_floats(const std::uint8_t* coded, std::size_t size, float* out, std::size_t n, std::span<const int> orders) {
    const std::size_t comps = orders.size(), count = n * comps;
    thread_local std::vector<std::uint8_t> planes;  // a block's at a time, kept between blocks of a thread
    planes.resize(count * 4);
    if (!inflate_raw(coded, size, planes.data(), planes.size())) return false;
    for (std::size_t k = 0; k < comps; ++k) {
        const std::uint8_t* p0 = planes.data() + k * n;
        const std::uint8_t *p1 = p0 + count, *p2 = p1 + count, *p3 = p2 + count;
        // the differences summed back in the same pass (u: the value, d: its first difference)
        std::uint32_t u = 0, d = 0;
        const int order = orders[k];
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t z = std::uint32_t(p0[i]) | std::uint32_t(p1[i]) << 8 | std::uint32_t(p2[i]) << 16 |
                                    std::uint32_t(p3[i]) << 24;
            const std::uint32_t v = unzigzag(z);
            if (order == 0) u = v;
            else if (order == 1) u += v;
            else d += v, u += d;
            out[i * comps + k] = unordered(u);
        }
    }
    return true;
}

std::vector<std::uint8_t> encode_bytes(const std::uint8_t* data, std::size_t n) { return deflate_raw(data, n); }

bool decode_bytes(const std::uint8_t* coded, std::size_t size, std::uint8_t* out, std::size_t n) {
    return inflate_raw(coded, size, out, n);
}

}  // namespace penink
