#include "drainage/line_tile_files.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/block_codec.hpp"
#include "core/cache_file_write.hpp"
#include "core/hash64.hpp"

namespace penink {

namespace {

constexpr std::uint32_t magic = 0x544c4e50u;  // "PNLT"
constexpr std::uint32_t version = 5;
// x, y, z, nx, ny, nz, flow: each differenced once along the vertices (neighbours on a line lie
// about a cell apart, their normals and flows alike)
constexpr std::array<int, 7> orders{1, 1, 1, 1, 1, 0, 1};  // nz: its residual (below), not differenced

// A unit normal's z from its x and y (the normals are upward: z >= 0), in double, rounded once.
float normal_z(float nx, float ny) {
    return float(std::sqrt(std::max(0.0, 1.0 - double(nx) * nx - double(ny) * ny)));
}
// nz stored as the zigzagged step of its bits from normal_z's (0 or a unit in the last place
// nearly always: a plane of zeros in place of one of noise), and back; lossless either way.
std::uint32_t float_bits(float f) { return std::bit_cast<std::uint32_t>(f); }
float nz_residual(const DrapedVertex& v) {
    const std::int32_t r = std::int32_t(float_bits(v.nz) - float_bits(normal_z(v.nx, v.ny)));
    return std::bit_cast<float>(std::uint32_t(r) << 1 ^ std::uint32_t(r >> 31));
}
float nz_of_residual(const DrapedVertex& v) {
    const std::uint32_t z = float_bits(v.nz), r = z >> 1 ^ (0u - (z & 1u));
    return std::bit_cast<float>(float_bits(normal_z(v.nx, v.ny)) + r);
}
static_assert(sizeof(DrapedVertex) == 7 * sizeof(float));

template <class T> void put(std::vector<std::uint8_t>& out, const T& v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), p, p + sizeof v);
}

struct Reader {
    const std::uint8_t* in;
    std::size_t size, at = 0;
    bool ok = true;
    template <class T> T get() {
        T v{};
        if (size - at < sizeof v) {
            ok = false;
            return v;
        }
        std::memcpy(&v, in + at, sizeof v);
        at += sizeof v;
        return v;
    }
};

// The vertices coded: each one's nz replaced by its residual, then encode_float_planes.
std::vector<std::uint8_t> encode_vertices(const DrapedVertices& vertices) {
    DrapedVertices v = vertices;
    for (DrapedVertex& x : v) x.nz = nz_residual(x);
    return encode_float_planes(reinterpret_cast<const float*>(v.data()), v.size(), orders);
}

}  // namespace

std::string line_tile_path(const std::string& folder, std::uint32_t tile, int level, int detail) {
    const std::string copy = detail > 0 ? "-d" + std::to_string(detail) : std::string();
    return (std::filesystem::path(folder) / ("tile-" + std::to_string(tile) + "-" + std::to_string(level) + copy + ".pnlt"))
        .string();
}

std::vector<std::uint8_t> encode_line_tile(std::uint64_t key, const DrapedLineSet& lines,
                                           const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds) {
    const std::vector<std::uint8_t> ids = encode_stem_ids(stems.data(), stems.size()),
                                    bound = encode_stem_bounds(bounds.data(), bounds.size()),
                                    coded = encode_vertices(lines.vertices);
    std::vector<std::uint8_t> out;
    out.reserve(64 + 5 * lines.lines.size() + ids.size() + bound.size() + coded.size());
    put(out, magic), put(out, version), put(out, key);
    put(out, std::uint32_t(lines.lines.size())), put(out, std::uint64_t(lines.vertices.size()));
    for (const DrapedLine& l : lines.lines) put(out, l.count), put(out, l.order);
    for (const std::vector<std::uint8_t>* part : {&ids, &bound, &coded}) {
        put(out, std::uint64_t(part->size()));
        out.insert(out.end(), part->begin(), part->end());
    }
    put(out, hash64(out.data(), out.size()));
    return out;
}

bool decode_line_tile(const std::uint8_t* data, std::size_t size, std::uint64_t key, TileLines& out) {
    if (size < 8) return false;
    std::uint64_t sum;
    std::memcpy(&sum, data + size - 8, 8);
    if (hash64(data, size - 8) != sum) return false;
    Reader r{data, size - 8};
    if (r.get<std::uint32_t>() != magic || r.get<std::uint32_t>() != version || r.get<std::uint64_t>() != key) return false;
    const auto nl = r.get<std::uint32_t>();
    const auto nv = r.get<std::uint64_t>();
    if (!r.ok || (r.size - r.at) / 5 < nl) return false;
    DrapedLineSet& lines = out.lines;
    lines = DrapedLineSet{};
    lines.lines.resize(nl);
    std::uint64_t first = 0;
    for (DrapedLine& l : lines.lines) {
        l.count = r.get<std::uint32_t>(), l.order = r.get<std::uint8_t>();
        l.first = std::uint32_t(first), first += l.count;
        if (l.count == 0 || first > nv) return false;
    }
    // a part's coded bytes: its size, then them
    auto part = [&r](const std::uint8_t*& at, std::uint64_t& n) {
        n = r.get<std::uint64_t>();
        if (!r.ok || n > r.size - r.at) return false;
        at = r.in + r.at, r.at += std::size_t(n);
        return true;
    };
    const std::uint8_t *ids, *bound, *coded;
    std::uint64_t ids_n, bound_n, coded_n;
    if (!part(ids, ids_n) || !part(bound, bound_n) || !part(coded, coded_n) || r.at != r.size) return false;
    std::vector<std::uint32_t>& stems = out.stems;
    stems.resize(nl), out.bounds.resize(nl);
    if (!decode_stem_ids(ids, std::size_t(ids_n), stems.data(), nl) ||
        !decode_stem_bounds(bound, std::size_t(bound_n), out.bounds.data(), nl))
        return false;
    // deflate packs at most 1032 bytes into one (RFC 1951: a 258-byte match in two bits at best):
    // the vertices' count is bounded by the coded size before anything is allocated
    if (first != nv || nv > (coded_n * 1032 + 1024) / sizeof(DrapedVertex)) return false;
    lines.vertices.resize(nv);
    if (!decode_float_planes(coded, std::size_t(coded_n), reinterpret_cast<float*>(lines.vertices.data()), nv, orders))
        return false;
    for (DrapedVertex& v : lines.vertices) v.nz = nz_of_residual(v);
    index_lines(lines);
    return line_set_ok(lines);
}

bool write_line_tile(const std::string& path, std::uint64_t key, const DrapedLineSet& lines,
                     const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds) {
    const std::vector<std::uint8_t> out = encode_line_tile(key, lines, stems, bounds);
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    return write_cache_file(path, {out}) == 0;
}

bool read_line_tile(const std::string& path, std::uint64_t key, TileLines& out) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    const auto size = std::filesystem::file_size(path, ec);
    std::ifstream f(path, std::ios::binary);
    if (ec || !f) return false;
    std::vector<std::uint8_t> in(size);
    if (!f.read(reinterpret_cast<char*>(in.data()), std::streamsize(size)) || f.peek() != EOF) return false;
    return decode_line_tile(in.data(), in.size(), key, out);
}

}  // namespace penink
