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
    std::vector<std::vector<std::uint8_t>> blocks(block_count(n));
    parallel_chunks(blocks.size(), 1, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b) blocks[b] = code(b * block_nodes, std::min(block_nodes, n - b * block_nodes));
    });
    put(out, std::uint32_t(blocks.size()));
    for (const auto& b : blocks) put(out, std::uint32_t(b.size()));
    for (const auto& b : blocks) out.insert(out.end(), b.begin(), b.end());
}

// Reads what put_blocks wrote for n elements, decoding block by block on all cores.
template <class Decode> bool get_blocks(Reader& r, std::size_t n, Decode decode) {
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

}  // namespace

std::vector<std::uint8_t> encode_crease_source(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                               const CreaseTileIndex& index) {
    std::vector<std::uint8_t> out;
    put(out, std::uint32_t(g.cols)), put(out, std::uint32_t(g.rows)), put(out, std::uint32_t(index.side));
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
    const std::size_t n = g.size();
    put_blocks(out, n, [&](std::size_t first, std::size_t k) { return encode_floats(g.z.data() + first, k, z_orders); });
    put_blocks(out, n, [&](std::size_t first, std::size_t k) { return encode_bytes(g.valid.data() + first, k); });
    put_blocks(out, n, [&](std::size_t first, std::size_t k) { return encode_bytes(dir.data() + first, k); });
    return out;
}

bool decode_crease_source(const std::uint8_t* data, std::size_t size, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index) {
    Reader r{data, size};
    std::uint32_t cols = 0, rows = 0, side = 0, tiles = 0;
    if (!r.get(cols) || !r.get(rows) || !r.get(side) || !r.get(tiles)) return false;
    if (int(cols) != g.cols || int(rows) != g.rows || side == 0 || side > (1u << 30)) return false;
    const std::uint64_t tx = (cols + std::uint64_t(side) - 1) / side, ty = (rows + std::uint64_t(side) - 1) / side;
    if (tiles != tx * ty || r.left / 16 < tiles) return false;
    index.side = int(side);
    if (!get_box(r, index.parts.lo, index.parts.hi)) return false;
    index.lo.resize(tiles), index.hi.resize(tiles);
    for (std::uint32_t k = 0; k < tiles; ++k) get_box(r, index.lo[k], index.hi[k]);
    const std::size_t n = g.size();
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
    g.z.resize(n), g.valid.resize(n), dir.resize(n);
    if (!get_blocks(r, n, [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
            return decode_floats(c, s, g.z.data() + first, k, z_orders);
        }))
        return false;
    if (!get_blocks(r, n, [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
            return decode_bytes(c, s, g.valid.data() + first, k);
        }))
        return false;
    if (!get_blocks(r, n, [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
            return decode_bytes(c, s, dir.data() + first, k);
        }))
        return false;
    return r.left == 0;
}

FlowNetwork network_of_directions(const DrainageGrid& g, const std::vector<std::uint8_t>& dir) {
    FlowNetwork net;
    const GridShape shape{g.cols, g.rows, g.valid.data()};
    run_beside([&] { label_basins(dir, shape, net); }, [&] { accumulate_flow(dir, shape, net); });
    return net;
}

}  // namespace penink
