#include "drainage/crease_source.hpp"

#include <array>
#include <cstring>

#include "core/block_codec.hpp"
#include "core/parallel_chunks.hpp"

namespace penink {
namespace {

constexpr unsigned block_shift = 16;
constexpr std::size_t block_nodes = std::size_t(1) << block_shift;
constexpr std::array<int, 1> z_orders{1};
constexpr std::array<int, 2> xy_orders{2, 2};  // x, y of a row's nodes: evenly spaced or nearly

template <class T> void put(std::vector<std::uint8_t>& out, T v) {
    const auto at = out.size();
    out.resize(at + sizeof v);
    std::memcpy(out.data() + at, &v, sizeof v);
}

struct Reader {
    const std::uint8_t* p;
    std::size_t left;
    template <class T> bool get(T& v) {
        if (left < sizeof v) return false;
        std::memcpy(&v, p, sizeof v);
        p += sizeof v, left -= sizeof v;
        return true;
    }
    bool take(std::size_t n, const std::uint8_t*& at) {
        if (left < n) return false;
        at = p, p += n, left -= n;
        return true;
    }
};

std::size_t block_count(std::size_t n) { return (n + block_nodes - 1) / block_nodes; }

// Codes n elements of `elem` bytes block by block on all cores, appended as count, sizes, bytes.
template <class Code> void put_blocks(std::vector<std::uint8_t>& out, std::size_t n, Code code) {
    put(out, std::uint64_t(n));
    std::vector<std::vector<std::uint8_t>> blocks(block_count(n));
    parallel_chunks(blocks.size(), 1, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b) blocks[b] = code(b * block_nodes, std::min(block_nodes, n - b * block_nodes));
    });
    put(out, std::uint32_t(blocks.size()));
    for (const auto& b : blocks) put(out, std::uint32_t(b.size()));
    for (const auto& b : blocks) out.insert(out.end(), b.begin(), b.end());
}

// Reads what put_blocks wrote for n elements, decoding block by block on all cores.
// n: the element count stored, which must be `want` or (with may_be_empty) 0; resize(n) sizes
// the output before the blocks are decoded.
template <class Resize, class Decode>
bool get_blocks(Reader& r, std::size_t want, bool may_be_empty, Resize resize, Decode decode) {
    std::uint64_t n = 0;
    if (!r.get(n) || !(n == want || (may_be_empty && n == 0))) return false;
    resize(std::size_t(n));
    std::uint32_t count = 0;
    if (!r.get(count) || count != block_count(n) || r.left / 4 < count) return false;
    std::vector<std::uint32_t> sizes(count);
    std::vector<const std::uint8_t*> at(count);
    for (auto& s : sizes) r.get(s);
    for (std::uint32_t b = 0; b < count; ++b)
        if (!r.take(sizes[b], at[b])) return false;
    std::vector<std::uint8_t> ok(count, 0);
    parallel_chunks(count, 1, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b)
            ok[b] = decode(at[b], sizes[b], b * block_nodes, std::min(block_nodes, n - b * block_nodes));
    });
    for (auto v : ok)
        if (!v) return false;
    return true;
}

void put_box(std::vector<std::uint8_t>& out, glm::vec2 lo, glm::vec2 hi) {
    put(out, lo.x), put(out, lo.y), put(out, hi.x), put(out, hi.y);
}
bool get_box(Reader& r, glm::vec2& lo, glm::vec2& hi) { return r.get(lo.x) && r.get(lo.y) && r.get(hi.x) && r.get(hi.y); }

// The stems' bounds [first, first + n) as ten byte planes (x0 and y0 each minus the stem
// before's in the block, x1 - x0, y1 - y0, length; the low bytes of a field, then its high
// bytes), deflated.
std::vector<std::uint8_t> encode_stem_bounds(const StemBound* b, std::size_t n) {
    std::vector<std::uint8_t> planes(10 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint16_t f[5] = {std::uint16_t(b[i].x0 - (i ? b[i - 1].x0 : 0)),
                                    std::uint16_t(b[i].y0 - (i ? b[i - 1].y0 : 0)), std::uint16_t(b[i].x1 - b[i].x0),
                                    std::uint16_t(b[i].y1 - b[i].y0), b[i].length};
        for (int k = 0; k < 5; ++k) planes[2 * k * n + i] = std::uint8_t(f[k]), planes[(2 * k + 1) * n + i] = std::uint8_t(f[k] >> 8);
    }
    return encode_bytes(planes.data(), planes.size());
}
bool decode_stem_bounds(const std::uint8_t* coded, std::size_t size, StemBound* b, std::size_t n) {
    std::vector<std::uint8_t> planes(10 * n);
    if (!decode_bytes(coded, size, planes.data(), planes.size())) return false;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint16_t f[5];
        for (int k = 0; k < 5; ++k) f[k] = std::uint16_t(planes[2 * k * n + i] | planes[(2 * k + 1) * n + i] << 8);
        b[i].x0 = std::uint16_t(f[0] + (i ? b[i - 1].x0 : 0)), b[i].y0 = std::uint16_t(f[1] + (i ? b[i - 1].y0 : 0));
        b[i].x1 = std::uint16_t(b[i].x0 + f[2]), b[i].y1 = std::uint16_t(b[i].y0 + f[3]), b[i].length = f[4];
    }
    return true;
}

}  // namespace

std::vector<std::uint8_t> encode_crease_source(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                               const CreaseTileIndex& index) {
    std::vector<std::uint8_t> out;
    put(out, std::uint32_t(g.cols)), put(out, std::uint32_t(g.rows)), put(out, std::int32_t(g.factor));
    put(out, g.dx), put(out, g.dy), put(out, g.origin.x), put(out, g.origin.y);
    put(out, std::int32_t(g.coarse_cols)), put(out, std::int32_t(g.coarse_rows)), put(out, std::uint32_t(g.has_affine));
    for (double v : g.affine.gt) put(out, v);
    put(out, g.affine.unit), put(out, std::int32_t(g.affine.col0)), put(out, std::int32_t(g.affine.row0));
    put(out, std::uint32_t(index.side));
    put(out, std::uint32_t(index.lo.size()));
    put_box(out, index.parts.lo, index.parts.hi);
    for (std::size_t k = 0; k < index.lo.size(); ++k) put_box(out, index.lo[k], index.hi[k]);
    const std::vector<std::uint32_t>& src = index.parts.sources;
    std::vector<std::uint32_t> deltas(src.size());
    for (std::size_t s = 0; s < src.size(); ++s) deltas[s] = src[s] - (s ? src[s - 1] : 0u);
    const std::vector<std::uint8_t> coded =
        encode_bytes(reinterpret_cast<const std::uint8_t*>(deltas.data()), deltas.size() * sizeof(std::uint32_t));
    put(out, std::uint64_t(src.size())), put(out, std::uint32_t(coded.size()));
    out.insert(out.end(), coded.begin(), coded.end());
    put_blocks(out, index.stems.size(),
               [&](std::size_t first, std::size_t k) { return encode_stem_bounds(index.stems.data() + first, k); });
    const std::size_t n = g.size();
    put_blocks(out, n, [&](std::size_t first, std::size_t k) { return encode_floats(g.z.data() + first, k, z_orders); });
    put_blocks(out, n, [&](std::size_t first, std::size_t k) { return encode_bytes(g.valid.data() + first, k); });
    put_blocks(out, n, [&](std::size_t first, std::size_t k) { return encode_bytes(dir.data() + first, k); });
    put_blocks(out, g.coarse_xy.size(), [&](std::size_t first, std::size_t k) {
        return encode_floats(&g.coarse_xy[first].x, k, xy_orders);
    });
    put_blocks(out, g.coarse_valid.size(),
               [&](std::size_t first, std::size_t k) { return encode_bytes(g.coarse_valid.data() + first, k); });
    put_blocks(out, g.coarse_z.size(),
               [&](std::size_t first, std::size_t k) { return encode_floats(g.coarse_z.data() + first, k, z_orders); });
    return out;
}

bool decode_crease_source(const std::uint8_t* data, std::size_t size, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index, bool arrays) {
    Reader r{data, size};
    std::uint32_t cols = 0, rows = 0, affine = 0, side = 0, tiles = 0;
    std::int32_t factor = 0, ccols = 0, crows = 0, col0 = 0, row0 = 0;
    g = DrainageGrid{};
    if (!r.get(cols) || !r.get(rows) || !r.get(factor) || !r.get(g.dx) || !r.get(g.dy) || !r.get(g.origin.x) ||
        !r.get(g.origin.y) || !r.get(ccols) || !r.get(crows) || !r.get(affine))
        return false;
    for (double& v : g.affine.gt)
        if (!r.get(v)) return false;
    if (!r.get(g.affine.unit) || !r.get(col0) || !r.get(row0) || !r.get(side) || !r.get(tiles)) return false;
    if (cols < 2 || rows < 2 || cols > (1u << 30) || rows > (1u << 30) || std::uint64_t(cols) * rows > (1ull << 32) ||
        factor < 1 || ccols < 2 || crows < 2 || std::uint64_t(ccols - 1) * std::uint64_t(factor) + 1 != cols ||
        std::uint64_t(crows - 1) * std::uint64_t(factor) + 1 != rows || affine > 1 || side == 0 || side > (1u << 30))
        return false;
    g.cols = int(cols), g.rows = int(rows), g.factor = factor, g.coarse_cols = ccols, g.coarse_rows = crows;
    g.has_affine = affine == 1, g.affine.col0 = col0, g.affine.row0 = row0;
    const std::uint64_t tx = (cols + std::uint64_t(side) - 1) / side, ty = (rows + std::uint64_t(side) - 1) / side;
    if (tiles != tx * ty || r.left / 16 < tiles) return false;
    index.side = int(side);
    if (!get_box(r, index.parts.lo, index.parts.hi)) return false;
    index.lo.resize(tiles), index.hi.resize(tiles);
    for (std::uint32_t k = 0; k < tiles; ++k) get_box(r, index.lo[k], index.hi[k]);
    const std::size_t n = g.size(), coarse = std::size_t(ccols) * std::size_t(crows);
    std::uint64_t sources = 0;
    std::uint32_t coded = 0;
    const std::uint8_t* at = nullptr;
    if (!r.get(sources) || sources > n || !r.get(coded) || !r.take(coded, at)) return false;
    std::vector<std::uint32_t>& src = index.parts.sources;
    src.resize(sources);
    if (!decode_bytes(at, coded, reinterpret_cast<std::uint8_t*>(src.data()), src.size() * sizeof(std::uint32_t)))
        return false;
    std::uint64_t cell = 0;
    for (std::size_t s = 0; s < src.size(); ++s) {
        if (s && src[s] == 0) return false;  // ascending
        cell += src[s];
        if (cell >= n) return false;
        src[s] = std::uint32_t(cell);
    }
    if (!get_blocks(
            r, src.size(), false, [&](std::size_t k) { index.stems.resize(k); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_stem_bounds(c, s, index.stems.data() + first, k);
            }))
        return false;
    auto floats = [&](std::vector<float>& v, std::size_t want, bool may_be_empty) {
        return get_blocks(
            r, want, may_be_empty, [&](std::size_t k) { v.resize(arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return !arrays || decode_floats(c, s, v.data() + first, k, z_orders);
            });
    };
    auto bytes = [&](std::vector<std::uint8_t>& v, std::size_t want, bool may_be_empty) {
        return get_blocks(
            r, want, may_be_empty, [&](std::size_t k) { v.resize(arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return !arrays || decode_bytes(c, s, v.data() + first, k);
            });
    };
    if (!floats(g.z, n, false) || !bytes(g.valid, n, false) || !bytes(dir, n, false)) return false;
    if (!get_blocks(
            r, coarse, true, [&](std::size_t k) { g.coarse_xy.resize(arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return !arrays || decode_floats(c, s, &g.coarse_xy[first].x, k, xy_orders);
            }))
        return false;
    if (!bytes(g.coarse_valid, coarse, true) || !floats(g.coarse_z, coarse, true)) return false;
    return r.left == 0;
}

FlowNetwork network_of_directions(const DrainageGrid& g, const std::vector<std::uint8_t>& dir) {
    FlowNetwork net;
    const GridShape shape{g.cols, g.rows, g.valid.data()};
    run_beside([&] { label_basins(dir, shape, net); }, [&] { accumulate_flow(dir, shape, net); });
    return net;
}

}  // namespace penink
