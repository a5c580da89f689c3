#include "drainage/line_tile_files.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <filesystem>
#include <fstream>

#include "core/block_codec.hpp"
#include "core/cache_file_write.hpp"
#include "core/hash64.hpp"

namespace penink {

namespace {

constexpr std::uint32_t magic = 0x544c4e50u;  // "PNLT"
constexpr std::uint32_t version = 8;
// A vertex's six codes (line_lattice.hpp: x, y, z, the normal's a and b, the flow), each
// predicted from the vertices before it on its line: x, y, z from the two before (a line's steps
// turn slowly: the step repeated), the others from the one before; a line's first vertex from the
// first of the line before (the tile's lines lie close), the second from the first.
constexpr int components = 6;
constexpr std::array<int, components> orders{2, 2, 2, 1, 1, 1};

using Codes = std::array<std::uint32_t, components>;
Codes codes_of(const VertexCode& c) {
    return {std::uint32_t(c.x), std::uint32_t(c.y), std::uint32_t(c.z), c.a, c.b, c.flow};
}
VertexCode code_of(const Codes& q) {
    return {std::int32_t(q[0]), std::int32_t(q[1]), std::int32_t(q[2]), q[3], q[4], q[5]};
}
// The prediction of component k of a line's vertex i >= 1 from its vertices i - 1 (p1) and i - 2
// (p2, read for i > 1 only), in 32-bit wrapping arithmetic; a line's first vertex is predicted by
// the first of the line before (0 for the tile's first line).
std::uint32_t predicted(const Codes& p1, const Codes& p2, std::uint32_t i, std::size_t k) {
    return i > 1 && orders[k] == 2 ? 2u * p1[k] - p2[k] : p1[k];
}
std::uint32_t zigzag(std::uint32_t r) { return r << 1 ^ (0u - (r >> 31)); }
std::uint32_t unzigzag(std::uint32_t z) { return z >> 1 ^ (0u - (z & 1u)); }

// The coded lines' bytes before deflating, in byte planes (a field's low bytes, then its next,
// ...: the high planes of small values are runs of zeros): first a row a line (its vertex count,
// u32; its order, u8; its first vertex's six residuals, u32 each), then a row for each other
// vertex (its six residuals), lines and vertices in order; plane p of a part of `rows` rows at
// part + p * rows.
struct Planes {
    static constexpr std::size_t line_planes = 4 + 1 + 4 * components, vertex_planes = 4 * components;
    std::size_t lines, others;  // rows of each part
    std::size_t size() const { return line_planes * lines + vertex_planes * others; }
    // the byte of field plane p (of a line's row or, `vertex`, another vertex's) in row `row`
    std::size_t at(bool vertex, std::size_t p, std::size_t row) const {
        return vertex ? line_planes * lines + p * others + row : p * lines + row;
    }
    void put(std::vector<std::uint8_t>& b, bool vertex, std::size_t p0, std::size_t row, std::uint32_t v) const {
        for (std::size_t k = 0; k < 4; ++k) b[at(vertex, p0 + k, row)] = std::uint8_t(v >> (8 * k));
    }
    std::uint32_t get(const std::vector<std::uint8_t>& b, bool vertex, std::size_t p0, std::size_t row) const {
        std::uint32_t v = 0;
        for (std::size_t k = 0; k < 4; ++k) v |= std::uint32_t(b[at(vertex, p0 + k, row)]) << (8 * k);
        return v;
    }
};
// a line row's planes: count 0-3, order 4, residual k at 5 + 4 k
constexpr std::size_t order_plane = 4, start_planes = 5;

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

// The lines and their vertices coded: each vertex's codes (vertex_code) less their predictions,
// zigzagged, in Planes, deflated (encode_bytes); empty when a vertex is not on the lattice.
std::vector<std::uint8_t> encode_lines(const DrapedLineSet& lines, const LineLattice& lattice) {
    const std::size_t n = lines.vertices.size();
    std::vector<Codes> q(n);
    for (std::size_t i = 0; i < n; ++i) {
        VertexCode c;
        if (!vertex_code(lines.vertices[i], lattice, c)) return {};
        q[i] = codes_of(c);
    }
    const Planes layout{lines.lines.size(), n - lines.lines.size()};
    std::vector<std::uint8_t> planes(layout.size());
    Codes before{};
    for (std::size_t j = 0, row = 0; j < lines.lines.size(); ++j) {
        const DrapedLine& l = lines.lines[j];
        layout.put(planes, false, 0, j, l.count);
        planes[layout.at(false, order_plane, j)] = l.order;
        for (std::size_t k = 0; k < components; ++k)
            layout.put(planes, false, start_planes + 4 * k, j, zigzag(q[l.first][k] - before[k]));
        for (std::uint32_t i = 1; i < l.count; ++i, ++row) {
            const std::size_t at = l.first + i;
            for (std::size_t k = 0; k < components; ++k)
                layout.put(planes, true, 4 * k, row, zigzag(q[at][k] - predicted(q[at - 1], q[at - (i > 1 ? 2 : 1)], i, k)));
        }
        before = q[l.first];
    }
    q = {};  // freed before deflating: the planes and their deflate at once at most
    std::vector<std::uint8_t> out = encode_bytes(planes.data(), planes.size());
    return out.empty() ? std::vector<std::uint8_t>{0} : out;  // never empty: empty says "not coded"
}

// `nl` lines of `nv` vertices in all from their coded bytes (encode_lines) into `lines` (counts,
// firsts, orders and vertices; boxes and index not made); false when they do not decode.
bool decode_lines(const std::uint8_t* coded, std::size_t size, std::size_t nl, std::size_t nv, const LineLattice& lattice,
                  DrapedLineSet& lines) {
    // deflate packs at most 1032 bytes into one (RFC 1951: a 258-byte match in two bits at best):
    // the planes' size (24 bytes a vertex or more) is bounded by the coded size before anything
    // is allocated
    if (nl > nv || nv > (size + 1) * (1032 / Planes::vertex_planes)) return false;
    const Planes layout{nl, nv - nl};
    if (layout.size() > (size + 1) * 1032) return false;
    std::vector<std::uint8_t> planes(layout.size());
    if (!decode_bytes(coded, size, planes.data(), planes.size())) return false;
    lines.lines.resize(nl);
    std::uint64_t first = 0;
    for (std::size_t j = 0; j < nl; ++j) {
        DrapedLine& l = lines.lines[j];
        l.count = layout.get(planes, false, 0, j), l.order = planes[layout.at(false, order_plane, j)];
        l.first = std::uint32_t(first), first += l.count;
        if (l.count == 0 || first > nv) return false;
    }
    if (first != nv) return false;
    // each component's residuals out of their four planes, then the codes line by line
    std::vector<std::uint32_t> starts(nl * components), others(layout.others * components);
    for (std::size_t k = 0; k < components; ++k) {
        const auto gather = [&](bool vertex, std::size_t rows, std::uint32_t* out) {
            const std::uint8_t* p[4];
            for (std::size_t b = 0; b < 4; ++b) p[b] = planes.data() + layout.at(vertex, (vertex ? 0 : start_planes) + 4 * k + b, 0);
            for (std::size_t j = 0; j < rows; ++j)
                out[j] = unzigzag(std::uint32_t(p[0][j]) | std::uint32_t(p[1][j]) << 8 | std::uint32_t(p[2][j]) << 16 |
                                  std::uint32_t(p[3][j]) << 24);
        };
        gather(false, nl, starts.data() + k * nl);
        gather(true, layout.others, others.data() + k * layout.others);
    }
    planes = {};  // each step's input freed once read: two of them at once at most
    std::vector<Codes> q(nv);
    Codes before{};
    for (std::size_t j = 0, row = 0; j < nl; ++j) {
        const DrapedLine& l = lines.lines[j];
        for (std::size_t k = 0; k < components; ++k) q[l.first][k] = before[k] + starts[k * nl + j];
        for (std::uint32_t i = 1; i < l.count; ++i, ++row) {
            const std::size_t at = l.first + i;
            for (std::size_t k = 0; k < components; ++k)
                q[at][k] = predicted(q[at - 1], q[at - (i > 1 ? 2 : 1)], i, k) + others[k * layout.others + row];
        }
        before = q[l.first];
    }
    starts = {}, others = {};
    std::vector<VertexCode> codes(nv);
    for (std::size_t i = 0; i < nv; ++i) codes[i] = code_of(q[i]);
    q = {};
    lines.vertices.resize(nv);
    lattice_vertices(codes.data(), nv, lattice, lines.vertices.data());
    return true;
}

}  // namespace

std::string line_tile_path(const std::string& folder, std::uint32_t tile, int level, int detail) {
    const std::string copy = detail > 0 ? "-d" + std::to_string(detail) : std::string();
    return (std::filesystem::path(folder) / ("tile-" + std::to_string(tile) + "-" + std::to_string(level) + copy + ".pnlt"))
        .string();
}

std::vector<std::uint8_t> encode_line_tile(std::uint64_t key, const LineLattice& lattice, const DrapedLineSet& lines,
                                           const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds,
                                           const TileRest& rest) {
    const std::vector<std::uint8_t> coded = encode_lines(lines, lattice);
    if (coded.empty()) return {};
    const std::vector<std::uint8_t> ids = encode_stem_ids(stems.data(), stems.size()),
                                    bound = encode_stem_bounds(bounds.data(), bounds.size());
    std::vector<std::uint8_t> rest_ids, rest_bound;  // (coded only where stems are left out)
    if (!rest.stems.empty())
        rest_ids = encode_stem_ids(rest.stems.data(), rest.stems.size()),
        rest_bound = encode_stem_bounds(rest.bounds.data(), rest.bounds.size());
    std::vector<std::uint8_t> out;
    out.reserve(96 + ids.size() + bound.size() + coded.size() + rest_ids.size() + rest_bound.size());
    put(out, magic), put(out, version), put(out, key);
    put(out, std::int32_t(lattice.plan_exp)), put(out, std::int32_t(lattice.z_exp));
    put(out, std::uint32_t(lines.lines.size())), put(out, std::uint64_t(lines.vertices.size()));
    put(out, std::uint32_t(rest.stems.size()));
    for (const std::vector<std::uint8_t>* part :
         std::initializer_list<const std::vector<std::uint8_t>*>{&ids, &bound, &coded, &rest_ids, &rest_bound}) {
        if (rest.stems.empty() && (part == &rest_ids || part == &rest_bound)) continue;
        put(out, std::uint64_t(part->size()));
        out.insert(out.end(), part->begin(), part->end());
    }
    put(out, hash64(out.data(), out.size()));
    return out;
}

bool decode_line_tile(const std::uint8_t* data, std::size_t size, std::uint64_t key, TileLines& out,
                      const TileNeed& need) {
    if (size < 8) return false;
    std::uint64_t sum;
    std::memcpy(&sum, data + size - 8, 8);
    if (hash64(data, size - 8) != sum) return false;
    Reader r{data, size - 8};
    if (r.get<std::uint32_t>() != magic || r.get<std::uint32_t>() != version || r.get<std::uint64_t>() != key) return false;
    LineLattice lattice;
    lattice.plan_exp = r.get<std::int32_t>(), lattice.z_exp = r.get<std::int32_t>();
    if (std::abs(lattice.plan_exp) > 126 || std::abs(lattice.z_exp) > 126) return false;
    const auto nl = r.get<std::uint32_t>();
    const auto nv = r.get<std::uint64_t>();
    const auto nr = r.get<std::uint32_t>();
    if (!r.ok) return false;
    // a part's coded bytes: its size, then them
    auto part = [&r](const std::uint8_t*& at, std::uint64_t& n) {
        n = r.get<std::uint64_t>();
        if (!r.ok || n > r.size - r.at) return false;
        at = r.in + r.at, r.at += std::size_t(n);
        return true;
    };
    const std::uint8_t *ids, *bound, *coded, *rest_ids = nullptr, *rest_bound = nullptr;
    std::uint64_t ids_n, bound_n, coded_n, rest_ids_n = 0, rest_bound_n = 0;
    if (!part(ids, ids_n) || !part(bound, bound_n) || !part(coded, coded_n) ||
        (nr && (!part(rest_ids, rest_ids_n) || !part(rest_bound, rest_bound_n))) || r.at != r.size)
        return false;
    out.rest.stems.resize(nr), out.rest.bounds.resize(nr);
    if (nr && (!decode_stem_ids(rest_ids, std::size_t(rest_ids_n), out.rest.stems.data(), nr) ||
               !decode_stem_bounds(rest_bound, std::size_t(rest_bound_n), out.rest.bounds.data(), nr)))
        return false;
    DrapedLineSet& lines = out.lines;
    lines = DrapedLineSet{};
    std::vector<std::uint32_t>& stems = out.stems;
    stems.resize(nl), out.bounds.resize(nl);
    if (!decode_stem_ids(ids, std::size_t(ids_n), stems.data(), nl) ||
        !decode_stem_bounds(bound, std::size_t(bound_n), out.bounds.data(), nl))
        return false;
    if (need && !need(out)) return true;
    if (!decode_lines(coded, std::size_t(coded_n), nl, std::size_t(nv), lattice, lines)) return false;
    index_lines(lines);
    return line_set_ok(lines);
}

bool write_line_tile(const std::string& path, std::uint64_t key, const LineLattice& lattice, const DrapedLineSet& lines,
                     const std::vector<std::uint32_t>& stems, const std::vector<StemBound>& bounds,
                     const TileRest& rest) {
    const std::vector<std::uint8_t> out = encode_line_tile(key, lattice, lines, stems, bounds, rest);
    if (out.empty()) return false;
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    return write_cache_file(path, {out}) == 0;
}

bool read_line_tile(const std::string& path, std::uint64_t key, TileLines& out, const TileNeed& need) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    const auto size = std::filesystem::file_size(path, ec);
    std::ifstream f(path, std::ios::binary);
    if (ec || !f) return false;
    std::vector<std::uint8_t> in(size);
    if (!f.read(reinterpret_cast<char*>(in.data()), std::streamsize(size)) || f.peek() != EOF) return false;
    return decode_line_tile(in.data(), in.size(), key, out, need);
}

}  // namespace penink
