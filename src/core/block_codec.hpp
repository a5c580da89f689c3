// Lossless coding of one block of a cache array, so a cache stores fewer bytes than the floats it
// holds and each block is still read and decoded on its own (core/checked_blocks.hpp).
//
// Floats (encode_floats): a block of n elements of orders.size() interleaved float32s each (a
// node's x, y, z; one error) is taken component by component; each float's bits are mapped to an
// unsigned integer in the order of the floats (negative ones reversed: the map is monotone, so
// neighbouring values on a smooth grid give neighbouring integers), differenced orders[k] times
// along the block (0: as they are; 1: each minus the previous; 2: the differences' differences,
// which vanish on a line sampled evenly: the x, y of a grid row),
// zigzag-mapped (small magnitudes to small integers), split into byte planes (all low bytes, then
// the next, ...: the high planes of small integers are runs of zeros), and deflated (libdeflate,
// raw DEFLATE stream, RFC 1951: any inflater reads it, so blocks coded by another deflater or
// level decode alike; the level and its measurement in block_codec.cpp). Decoding inverts each step exactly: the floats come back bit for bit (NaN payloads,
// signed zeros and infinities included).
// Bytes (encode_bytes): deflated as they are.
// decode_* return false when the coded bytes do not inflate to exactly the block's size (a
// damaged or foreign block); the cache checks a checksum of the coded bytes before decoding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace penink {

// n elements of orders.size() float32s each, at `data`; each order 0, 1 or 2.
std::vector<std::uint8_t> encode_floats(const float* data, std::size_t n, std::span<const int> orders);
bool decode_floats(const std::uint8_t* coded, std::size_t size, float* out, std::size_t n, std::span<const int> orders);

// The same planes, each deflated on its own and kept as it is where deflate does not bring it
// under raw_plane_share of its size (the low bytes of a difference are near random: inflating
// them costs time and saves nothing), so decoding inflates only the planes that code smaller; a
// plane of over 16 384 bytes whose first 16 384 do not code under that share is kept as it is
// without deflating the rest.
// Layout: per plane (4 x orders.size() of n bytes, low bytes first) u64 coded size (0: raw, n
// bytes follow) and its bytes.
inline constexpr double raw_plane_share = 0.9;
std::vector<std::uint8_t> encode_float_planes(const float* data, std::size_t n, std::span<const int> orders);
bool decode_float_planes(const std::uint8_t* coded, std::size_t size, float* out, std::size_t n,
                         std::span<const int> orders);

std::vector<std::uint8_t> encode_bytes(const std::uint8_t* data, std::size_t n);
bool decode_bytes(const std::uint8_t* coded, std::size_t size, std::uint8_t* out, std::size_t n);

}  // namespace penink
