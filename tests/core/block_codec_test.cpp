// Block coding: floats come back bit for bit at every differencing order (signed zeros, NaN
// payloads, infinities, subnormals, random bits), bytes too; a smooth grid row codes to far fewer
// bytes than its floats, and more so differenced twice; coded bytes cut short, damaged or of
// another length do not decode; coded plane by plane, the near-random planes are kept as they are.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/block_codec.hpp"

using namespace penink;

namespace {

void expect_same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(a[i]), std::bit_cast<std::uint32_t>(b[i])) << i;
}

// 256 nodes of a grid row: x east 3.1 m apart, y gently curved, z a smooth slope (metres).
std::vector<float> grid_row() {
    std::vector<float> v;
    for (int i = 0; i < 256; ++i) {
        const double x = -400.0 + 3.1 * i;
        v.push_back(float(x));
        v.push_back(float(1234.5 + 1e-5 * x * x));
        v.push_back(float(250.0 + 20.0 * std::sin(x / 90.0)));
    }
    return v;
}

}  // namespace

TEST(BlockCodec, FloatsComeBackBitForBitAtEveryOrder) {
    std::mt19937 rng(7);
    std::vector<float> v = grid_row();
    const float odd[] = {0.0f, -0.0f, std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                         std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::max(),
                         std::bit_cast<float>(0x7fc12345u), std::bit_cast<float>(0xffa00001u)};
    for (std::size_t i = 0; i < std::size(odd); ++i) v[i * 7] = odd[i];
    for (int i = 0; i < 30; ++i) v[100 + i] = std::bit_cast<float>(std::uint32_t(rng()));  // random bits
    for (const int comps : {1, 3})
        for (const int order : {0, 1, 2}) {
            SCOPED_TRACE(testing::Message() << comps << " components, order " << order);
            const std::size_t n = v.size() / std::size_t(comps);
            const std::vector<int> orders(std::size_t(comps), order);
            const std::vector<std::uint8_t> c = encode_floats(v.data(), n, orders);
            std::vector<float> back(v.size(), 1.0f);
            ASSERT_TRUE(decode_floats(c.data(), c.size(), back.data(), n, orders));
            expect_same_bits(v, back);
        }
    // a short last block, and a block of one
    std::vector<float> back(6);
    const int mixed[3] = {2, 2, 1};
    const std::vector<std::uint8_t> c = encode_floats(v.data(), 2, mixed);
    ASSERT_TRUE(decode_floats(c.data(), c.size(), back.data(), 2, mixed));
    expect_same_bits(std::vector<float>(v.begin(), v.begin() + 6), back);
}

// A smooth row codes to under a third of its 12 bytes a node differenced twice (x, y: second
// differences of a near-linear row are a few units in the last place), and to fewer bytes than
// differenced once or not at all.
TEST(BlockCodec, ASmoothRowCodesSmall) {
    const std::vector<float> v = grid_row();
    std::size_t size[3];
    for (int order = 0; order < 3; ++order) size[order] = encode_floats(v.data(), 256, std::vector<int>(3, order)).size();
    std::printf("256 nodes of a smooth row: %zu, %zu, %zu bytes at orders 0, 1, 2 (%zu as floats)\n", size[0], size[1],
                size[2], v.size() * 4);
    EXPECT_LT(size[2] * 3, v.size() * 4);
    EXPECT_LT(size[2], size[1]);
    EXPECT_LT(size[1], size[0]);
}

TEST(BlockCodec, BytesComeBackAndARunOfOnesCodesToAFewBytes) {
    std::vector<std::uint8_t> v(256, 1);
    for (int i = 40; i < 60; ++i) v[std::size_t(i)] = 0;
    const std::vector<std::uint8_t> c = encode_bytes(v.data(), v.size());
    EXPECT_LT(c.size(), 20u);
    std::vector<std::uint8_t> back(v.size(), 7);
    ASSERT_TRUE(decode_bytes(c.data(), c.size(), back.data(), back.size()));
    EXPECT_EQ(back, v);
}

TEST(BlockCodec, DamagedShortOrMisfitCodedBytesDoNotDecode) {
    const std::vector<float> v = grid_row();
    const int orders[3] = {2, 2, 2};
    const std::vector<std::uint8_t> c = encode_floats(v.data(), 256, orders);
    std::vector<float> back(v.size());
    EXPECT_FALSE(decode_floats(c.data(), c.size() - 1, back.data(), 256, orders));      // cut short
    EXPECT_FALSE(decode_floats(c.data(), c.size(), back.data(), 255, orders));          // longer than said
    std::vector<std::uint8_t> extra = c;
    extra.push_back(0);
    EXPECT_FALSE(decode_floats(extra.data(), extra.size(), back.data(), 256, orders));  // bytes after the stream
    const std::uint8_t junk[] = {0xff, 0xff, 0xff, 0xff, 0xff, 0xff};
    EXPECT_FALSE(decode_floats(junk, sizeof junk, back.data(), 256, orders));
    EXPECT_FALSE(decode_bytes(junk, sizeof junk, reinterpret_cast<std::uint8_t*>(back.data()), 16));
}

// Plane by plane: the floats come back bit for bit; the near-random low planes of the row's
// random-bit stretch are kept as they are (a coded size of 0), the high planes of the smooth part
// deflated; cut short, longer or with bytes after, they do not decode.
TEST(BlockCodec, PlanesComeBackBitForBitTheRandomOnesKeptAsTheyAre) {
    std::mt19937 rng(9);
    std::vector<float> v = grid_row();
    for (std::size_t i = 0; i < v.size(); i += 3) v[i] = std::bit_cast<float>(std::uint32_t(rng()));  // x: random bits
    const int orders[3] = {1, 1, 1};
    const std::vector<std::uint8_t> c = encode_float_planes(v.data(), 256, orders);
    std::vector<float> back(v.size(), 1.0f);
    ASSERT_TRUE(decode_float_planes(c.data(), c.size(), back.data(), 256, orders));
    expect_same_bits(v, back);
    // twelve planes, each with its 8-byte size; x's four random planes raw (256 bytes and a 0 size)
    std::size_t raw = 0, coded = 0, at = 0;
    for (int p = 0; p < 12; ++p) {
        std::uint64_t len;
        std::memcpy(&len, c.data() + at, 8);
        at += 8 + (len == 0 ? 256 : len);
        (len == 0 ? raw : coded) += 1;
    }
    EXPECT_EQ(at, c.size());
    EXPECT_GE(raw, 4u);
    EXPECT_GE(coded, 4u);  // the high planes of y and z
    EXPECT_FALSE(decode_float_planes(c.data(), c.size() - 1, back.data(), 256, orders));
    EXPECT_FALSE(decode_float_planes(c.data(), c.size(), back.data(), 255, orders));
    std::vector<std::uint8_t> extra = c;
    extra.push_back(0);
    EXPECT_FALSE(decode_float_planes(extra.data(), extra.size(), back.data(), 256, orders));
}

// Planes longer than the 16 384-byte sample: a random plane is kept as it is (found from its
// sample), a smooth one deflated; both come back bit for bit.
TEST(BlockCodec, LongPlanesKeptAsTheyAreFromTheirSample) {
    std::mt19937 rng(11);
    const std::size_t n = 40000;
    std::vector<float> v(2 * n);
    for (std::size_t i = 0; i < n; ++i)
        v[2 * i] = std::bit_cast<float>(std::uint32_t(rng())), v[2 * i + 1] = float(100.0 + 0.25 * double(i % 512));
    const int orders[2] = {1, 1};
    const std::vector<std::uint8_t> c = encode_float_planes(v.data(), n, orders);
    std::vector<float> back(v.size());
    ASSERT_TRUE(decode_float_planes(c.data(), c.size(), back.data(), n, orders));
    expect_same_bits(v, back);
    std::size_t raw = 0, at = 0;
    for (int p = 0; p < 8; ++p) {
        std::uint64_t len;
        std::memcpy(&len, c.data() + at, 8);
        at += 8 + (len == 0 ? n : len);
        raw += len == 0;
    }
    EXPECT_EQ(at, c.size());
    EXPECT_EQ(raw, 4u);                      // the random component's four planes
    EXPECT_LT(c.size(), 4 * n + 4 * n / 4);  // the smooth one's in under a quarter of theirs
}
