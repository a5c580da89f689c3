#include "core/block_codec.hpp"

#include <algorithm>
#include <bit>
#include <array>
#include <cstring>
#include <new>

#include <libdeflate.h>

namespace penink {

namespace {

// libdeflate level 5, chosen by measurement on every block of the terrain cache of jacksboro
// refined 10 times (13.9 M nodes, 174 k blocks; x, y derived: heights, flags and pyramid errors;
// one thread, CPU seconds at a load of about 4):
//   coder                 bytes      code s  decode s
//   zlib 2 (window 2^12)  15.94 M    1.04    0.38     (what the cache used before)
//   libdeflate 1          14.95 M    1.04    0.29
//   libdeflate 2-4        14.50-14.57 M  1.32-1.41  0.28
//   libdeflate 5          14.14 M    1.54    0.27
//   libdeflate 6 (its default) 14.11 M  1.65  0.27
//   libdeflate 8, 9       14.00 M    2.94-3.73  0.26
// Decoding, which every frame pays, takes about the same at every level (a quarter less than
// zlib's inflate); the level trades the cache's one build against its size, and 5 is the knee:
// its lazy matching takes 2.5 % off level 4 for 9 % more coding, the levels above it 1 % at most
// for 7 to 140 % more. Coding is paid once per DEM: 0.5 s more than zlib here, against the
// cold build's 14 s of drainage. (Measured by inflating the blocks of a .lod and coding them
// again at each level.)
constexpr int deflate_level = 5;

// A compressor and a decompressor per thread (each used by one thread at a time; allocating one
// per block would cost more than coding it).
struct Codecs {
    libdeflate_compressor* c = nullptr;
    libdeflate_decompressor* d = nullptr;
    ~Codecs() { libdeflate_free_compressor(c), libdeflate_free_decompressor(d); }
};
Codecs& thread_codecs() {
    thread_local Codecs codecs;
    return codecs;
}
libdeflate_compressor* compressor() {
    Codecs& k = thread_codecs();
    if (!k.c && !(k.c = libdeflate_alloc_compressor(deflate_level))) throw std::bad_alloc();
    return k.c;
}
libdeflate_decompressor* decompressor() {
    Codecs& k = thread_codecs();
    if (!k.d && !(k.d = libdeflate_alloc_decompressor())) throw std::bad_alloc();
    return k.d;
}

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
    libdeflate_compressor* c = compressor();
    std::vector<std::uint8_t> out(libdeflate_deflate_compress_bound(c, n));
    const std::size_t size = libdeflate_deflate_compress(c, data, n, out.data(), out.size());
    if (size == 0) throw std::bad_alloc();  // the bound guarantees room: cannot happen
    out.resize(size);
    out.shrink_to_fit();  // the bound's room (about the input's size) would stay with every block held
    return out;
}

// Inflates exactly n bytes from exactly `size` coded bytes; false otherwise.
bool inflate_raw(const std::uint8_t* coded, std::size_t size, std::uint8_t* out, std::size_t n) {
    std::size_t in = 0, got = 0;
    return libdeflate_deflate_decompress_ex(decompressor(), coded, size, out, n, &in, &got) == LIBDEFLATE_SUCCESS &&
           in == size && got == n;
}

}  // namespace

namespace {

// The byte planes of n elements of orders.size() floats (all low bytes of component 0, then of
// component 1, ..., then the next byte of each): the floats ordered, differenced, zigzagged.
std::vector<std::uint8_t> float_planes(const float* data, std::size_t n, std::span<const int> orders) {
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
    return planes;
}

// float_planes inverted into `out`.
void planes_to_floats(const std::uint8_t* planes, float* out, std::size_t n, std::span<const int> orders) {
    const std::size_t comps = orders.size(), count = n * comps;
    // the differences summed back in the same pass (u: a component's value, d: its first
    // difference), a run of elements at a time so that the interleaved output written component by
    // component stays in cache
    constexpr std::size_t run = 1024;
    // each component's running value and difference (on the stack for a few components: a block
    // of a terrain cache decodes in a few microseconds, an allocation would be a tenth of it)
    constexpr std::size_t few = 4;
    std::array<std::uint32_t, few> u_few{}, d_few{};
    std::vector<std::uint32_t> u_many, d_many;
    if (comps > few) u_many.assign(comps, 0), d_many.assign(comps, 0);
    std::uint32_t* u = comps > few ? u_many.data() : u_few.data();
    std::uint32_t* d = comps > few ? d_many.data() : d_few.data();
    for (std::size_t i0 = 0; i0 < n; i0 += run) {
        const std::size_t i1 = std::min(n, i0 + run);
        for (std::size_t k = 0; k < comps; ++k) {
            const std::uint8_t* p0 = planes + k * n;
            const std::uint8_t *p1 = p0 + count, *p2 = p1 + count, *p3 = p2 + count;
            std::uint32_t uk = u[k], dk = d[k];
            const int order = orders[k];
            for (std::size_t i = i0; i < i1; ++i) {
                const std::uint32_t z = std::uint32_t(p0[i]) | std::uint32_t(p1[i]) << 8 | std::uint32_t(p2[i]) << 16 |
                                        std::uint32_t(p3[i]) << 24;
                const std::uint32_t v = unzigzag(z);
                if (order == 0) uk = v;
                else if (order == 1) uk += v;
                else dk += v, uk += dk;
                out[i * comps + k] = unordered(uk);
            }
            u[k] = uk, d[k] = dk;
        }
    }
}

}  // namespace

std::vector<std::uint8_t> encode_floats(const float* data, std::size_t n, std::span<const int> orders) {
    const std::vector<std::uint8_t> planes = float_planes(data, n, orders);
    return deflate_raw(planes.data(), planes.size());
}

bool decode_floats(const std::uint8_t* coded, std::size_t size, float* out, std::size_t n, std::span<const int> orders) {
    thread_local std::vector<std::uint8_t> planes;  // a block's at a time, kept between blocks of a thread
    planes.resize(n * orders.size() * 4);
    if (!inflate_raw(coded, size, planes.data(), planes.size())) return false;
    planes_to_floats(planes.data(), out, n, orders);
    return true;
}

namespace {
constexpr std::size_t plane_sample = 16384;
}  // namespace

std::vector<std::uint8_t> encode_float_planes(const float* data, std::size_t n, std::span<const int> orders) {
    const std::vector<std::uint8_t> planes = float_planes(data, n, orders);
    std::vector<std::uint8_t> out;
    for (std::size_t at = 0; at < planes.size(); at += n) {
        // a plane whose first plane_sample bytes do not code under the share is kept as it is
        // without deflating the rest (the low planes of differences: deflating near-random bytes
        // is deflate's slowest work)
        const std::size_t sample = std::min(n, plane_sample);
        const bool random =
            sample < n && double(deflate_raw(planes.data() + at, sample).size()) > raw_plane_share * double(sample);
        const std::vector<std::uint8_t> coded = random ? std::vector<std::uint8_t>() : deflate_raw(planes.data() + at, n);
        const bool raw = random || double(coded.size()) > raw_plane_share * double(n);
        const std::uint64_t size = raw ? 0 : coded.size();  // 0: the plane's n bytes as they are
        const auto* p = reinterpret_cast<const std::uint8_t*>(&size);
        out.insert(out.end(), p, p + sizeof size);
        if (raw) out.insert(out.end(), planes.begin() + std::ptrdiff_t(at), planes.begin() + std::ptrdiff_t(at + n));
        else out.insert(out.end(), coded.begin(), coded.end());
    }
    return out;
}

bool decode_float_planes(const std::uint8_t* coded, std::size_t size, float* out, std::size_t n,
                         std::span<const int> orders) {
    const std::size_t count = n * orders.size() * 4;
    thread_local std::vector<std::uint8_t> planes;
    planes.resize(count);
    std::size_t in = 0;
    for (std::size_t at = 0; at < count; at += n) {
        std::uint64_t len;
        if (size - in < sizeof len) return false;
        std::memcpy(&len, coded + in, sizeof len);
        in += sizeof len;
        const std::uint64_t take = len == 0 ? n : len;
        if (size - in < take) return false;
        if (len == 0) std::memcpy(planes.data() + at, coded + in, n);
        else if (!inflate_raw(coded + in, len, planes.data() + at, n)) return false;
        in += take;
    }
    if (in != size) return false;
    planes_to_floats(planes.data(), out, n, orders);
    return true;
}

std::vector<std::uint8_t> encode_bytes(const std::uint8_t* data, std::size_t n) { return deflate_raw(data, n); }

bool decode_bytes(const std::uint8_t* coded, std::size_t size, std::uint8_t* out, std::size_t n) {
    return inflate_raw(coded, size, out, n);
}

}  // namespace penink
