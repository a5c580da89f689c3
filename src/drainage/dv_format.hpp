// The DV file layout shared by its writer (dv_writer.cpp) and reader (dv_reader.cpp); the layout
// itself is set out at the top of drainage_db.cpp. Internal to src/drainage.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "drainage/drainage_db.hpp"
#include "drainage/flow_network.hpp"

namespace penink::dv {

inline constexpr char magic[8] = {'P', 'N', 'K', 'D', 'V', 0, 0, 0};
// magic, version, reserved, total length, offset of the lines part
inline constexpr std::size_t prefix_bytes = 8 + 4 + 4 + 8 + 8;

// How the network is stored (the byte after the CRS): branches with x, y per vertex, or with
// grid cells on an affine grid (then f64 gt[6], f64 unit, i32 col0, row0 follow), or not at all:
// the crease source in the lines part gives it (only the counts are stored).
inline constexpr std::uint8_t positions_explicit = 0, positions_grid = 1, positions_source = 2;

// LEB128 varint of v at p (at most 10 bytes); returns the byte after it.
inline std::uint8_t* put_varint(std::uint8_t* p, std::uint64_t v) {
    for (; v >= 0x80; v >>= 7) *p++ = std::uint8_t(v | 0x80);
    *p++ = std::uint8_t(v);
    return p;
}

// Vertices of a branch the file stores (all but a repeated end junction).
inline std::uint32_t stored_count(const DvBranchRecord& r) { return r.count - (r.downstream >= 0); }

// Bytes of a branch's stored vertices: 12 each with explicit positions; on grid nodes 4 for the
// head and 5 for each next one.
inline std::size_t vertex_bytes(const DvBranchRecord& r, bool grid) {
    const std::size_t n = stored_count(r);
    return grid ? (n ? 5 * n - 1 : 0) : 12 * n;
}

// Most bytes a branch record takes: five varints, the order byte and (grid) the head-cell delta.
inline constexpr std::size_t max_record_bytes = 6 * 10 + 1;

// Appends the record of branch `id` at p (the head-cell delta from the branch before only on grid
// nodes); returns the byte after it. Its vertices follow (vertex_bytes of them).
inline std::uint8_t* put_record(std::uint8_t* p, const DvBranchRecord& r, std::size_t id, bool grid,
                                std::uint32_t head_delta) {
    std::uint64_t link = 0;  // 0 at an outlet, else the zigzag of the step to the downstream branch
    if (r.downstream >= 0) {
        const std::int64_t d = std::int64_t(r.downstream) - std::int64_t(id);
        link = d >= 0 ? std::uint64_t(d) << 1 : (std::uint64_t(-d) << 1) - 1;
    }
    p = put_varint(p, r.count), p = put_varint(p, link);
    *p++ = r.order;
    p = put_varint(p, r.basin), p = put_varint(p, r.head_acc);
    return grid ? put_varint(p, head_delta) : p;
}

// Appends branch `id` to `out` as the file stores it: its record (put_record), then its stored
// vertices, which put_vertices(p) writes from p on and returns the byte after (at most
// vertex_bytes of them; `out` is trimmed to what was written).
template <class PutVertices>
void append_branch(DvBytes& out, const DvBranchRecord& r, std::size_t id, bool grid, std::uint32_t head_delta,
                   PutVertices&& put_vertices) {
    const std::size_t at = out.size();
    out.resize(at + max_record_bytes + vertex_bytes(r, grid));
    std::uint8_t* p = put_vertices(put_record(out.data() + at, r, id, grid, head_delta));
    out.resize(std::size_t(p - out.data()));
}

// Where the total file length and the offset of the lines part sit: written as 0 while streaming
// and filled in at the end; the checksums hash them as 0 in place and then as their last words.
inline constexpr std::size_t total_length_at = 16, lines_at_at = 24;

// The network part's checksum: file bytes [0, lines_at - 8) (lines_at a multiple of 8) with the
// two length fields read as 0, then lines_at.
inline std::uint64_t network_hash(const std::uint8_t* b, std::uint64_t lines_at) {
    const std::uint64_t zero[2] = {0, 0};
    std::uint64_t h = hash64(b, total_length_at);
    h = hash64(zero, 16, h);
    h = hash64(b + prefix_bytes, std::size_t(lines_at - 8 - prefix_bytes), h);
    return hash64(&lines_at, 8, h);
}

// The lines part's checksum: its bytes `part` (from lines_at to the checksum), then lines_at and
// the total length.
inline std::uint64_t lines_hash(const std::uint8_t* part, std::size_t n, std::uint64_t lines_at, std::uint64_t total) {
    std::uint64_t h = hash64(part, n);
    h = hash64(&lines_at, 8, h);
    return hash64(&total, 8, h);
}

// hash64 of a concatenation of byte runs fed one after another (whole 8-byte words, the last
// bytes one by one), as if they were one array.
struct ConcatHash {
    std::uint64_t h = hash64(nullptr, 0);
    std::uint8_t tail[8] = {};
    std::size_t tail_n = 0;
    void feed(const std::uint8_t* p, std::size_t n) {
        if (tail_n) {
            const std::size_t k = n < 8 - tail_n ? n : 8 - tail_n;
            for (std::size_t i = 0; i < k; ++i) tail[tail_n + i] = p[i];
            tail_n += k, p += k, n -= k;
            if (tail_n < 8) return;
            h = hash64(tail, 8, h), tail_n = 0;
        }
        const std::size_t whole = n & ~std::size_t(7);
        h = hash64(p, whole, h);
        for (std::size_t i = whole; i < n; ++i) tail[i - whole] = p[i];
        tail_n = n - whole;
    }
    std::uint64_t digest() const { return hash64(tail, tail_n, h); }
};

// Vertices of a line set checked by one checksum of the lines part (its block checksums follow
// the set's vertex array).
inline constexpr std::uint64_t vertex_block = 1024;
inline std::uint64_t vertex_blocks(std::uint64_t vertices) { return (vertices + vertex_block - 1) / vertex_block; }
// hash64 of block k of the n vertices at v.
inline std::uint64_t vertex_block_hash(const DrapedVertex* v, std::uint64_t n, std::uint64_t k) {
    const std::uint64_t first = k * vertex_block, count = n - first < vertex_block ? n - first : vertex_block;
    return hash64(v + first, std::size_t(count * sizeof(DrapedVertex)));
}

// One line as the lines part stores it (28 bytes): f32 lo.x, lo.y, hi.x, hi.y, length; u32
// count; u8 order; 3 zero bytes.
inline constexpr std::size_t line_record_bytes = 28;

// Accumulation at the outlet of basin b at total[b - 1], from the basin's outlet branch. False
// unless every basin id is in 1..outlet branches, each outlet branch has its own and its total
// is at least one point.
bool basin_totals(const DrainageDb& db, std::vector<double>& total);

// Normalised flow at vertex k of branch b (as the builder's normalised_flow gives it).
inline float branch_flow(const DvBranch& b, std::uint32_t k, const std::vector<double>& total) {
    return flow_of(std::uint64_t(b.head_acc) + k, total[b.basin - 1]);
}

// What the layout relies on and the encoder checks (drainage_db.cpp): vertex ranges of branches
// and divides consecutive, downstream links in range and never to the branch itself, basin ids.
bool layout_ok(const DrainageDb& db);

}  // namespace penink::dv
