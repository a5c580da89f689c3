#include "drainage/crease_source.hpp"

#include <array>
#include <cstring>
#include <filesystem>

#include "core/block_codec.hpp"
#include "core/error.hpp"
#include "core/hash64.hpp"
#include "core/parallel_chunks.hpp"
#include "input/dem_reader.hpp"

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

// Reads bytes of a source in order; from a file, the pages of what it gets or takes are read
// (checked) first, those it skips are not.
struct Reader {
    const std::uint8_t* p;
    std::size_t left;
    const CreaseSourceBytes* src = nullptr;
    template <class T> bool get(T& v) {
        if (left < sizeof v) return false;
        touch(sizeof v);
        std::memcpy(&v, p, sizeof v);
        p += sizeof v, left -= sizeof v;
        return true;
    }
    bool take(std::size_t n, const std::uint8_t*& at) {
        if (left < n) return false;
        touch(n);
        at = p, p += n, left -= n;
        return true;
    }
    bool skip(std::size_t n) {
        if (left < n) return false;
        p += n, left -= n;
        return true;
    }
    void touch(std::size_t n) const {
        if (src) src->need(std::uint64_t(p - src->data), n);
    }
};

std::size_t block_count(std::size_t n) { return (n + block_nodes - 1) / block_nodes; }

// Codes n elements block by block on all cores (code(first, count) codes one block).
template <class Code> CodedSourceArray code_blocks(std::size_t n, Code code) {
    CodedSourceArray a;
    a.elements = n;
    a.blocks.resize(block_count(n));
    parallel_chunks(a.blocks.size(), 1, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b) {
            a.blocks[b] = code(b * block_nodes, std::min(block_nodes, n - b * block_nodes));
            a.blocks[b].shrink_to_fit();  // the coder's room for the worst case given back: arrays wait to be assembled
        }
    });
    return a;
}

// Appends a coded array as count, blocks, sizes, bytes.
void put_blocks(std::vector<std::uint8_t>& out, const CodedSourceArray& a) {
    put(out, a.elements);
    put(out, std::uint32_t(a.blocks.size()));
    for (const auto& b : a.blocks) put(out, std::uint32_t(b.size()));
    for (const auto& b : a.blocks) out.insert(out.end(), b.begin(), b.end());
}

// At factor 1 the coarse nodes are the fine ones: their mask is g.valid, not stored twice.
bool coarse_valid_shared(const DrainageGrid& g) {
    return g.factor == 1 && (g.coarse_valid.empty() || g.coarse_valid == g.valid);  // (empty: left out, the same)
}

// Reads what put_blocks wrote, decoding block by block on all cores (read = false: the blocks
// passed over, not decoded). The element count stored must satisfy accept(n); resize(n) sizes
// the output before the blocks are decoded.
template <class Accept, class Resize, class Decode>
bool get_blocks(Reader& r, Accept accept, Resize resize, Decode decode, bool read = true) {
    std::uint64_t n = 0;
    if (!r.get(n) || !accept(n)) return false;
    resize(std::size_t(n));
    std::uint32_t count = 0;
    if (!r.get(count) || count != block_count(n) || r.left / 4 < count) return false;
    std::vector<std::uint32_t> sizes(count);
    std::vector<const std::uint8_t*> at(count);
    for (auto& s : sizes) r.get(s);
    if (!read) {
        for (std::uint32_t b = 0; b < count; ++b)
            if (!r.skip(sizes[b])) return false;
        return true;
    }
    std::size_t all = 0;  // the blocks taken at once: one read of their pages
    for (std::uint32_t b = 0; b < count; ++b) all += sizes[b];
    const std::uint8_t* p = nullptr;
    if (!r.take(all, p)) return false;
    for (std::uint32_t b = 0; b < count; ++b) at[b] = p, p += sizes[b];
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

CodedSourceArray code_source_array(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, SourceArray a) {
    auto floats = [](const std::vector<float>& v) {
        return code_blocks(v.size(), [&](std::size_t first, std::size_t k) { return encode_floats(v.data() + first, k, z_orders); });
    };
    auto bytes = [](const std::vector<std::uint8_t>& v, std::size_t n) {
        return code_blocks(n, [&](std::size_t first, std::size_t k) { return encode_bytes(v.data() + first, k); });
    };
    switch (a) {
        case SourceArray::z: return floats(g.z);
        case SourceArray::valid: return bytes(g.valid, g.valid.size());
        case SourceArray::dir: return bytes(dir, dir.size());
        case SourceArray::coarse_xy:
            return code_blocks(g.coarse_xy.size(), [&](std::size_t first, std::size_t k) {
                return encode_floats(&g.coarse_xy[first].x, k, xy_orders);
            });
        case SourceArray::coarse_valid:
            return bytes(g.coarse_valid, coarse_valid_shared(g) ? 0 : g.coarse_valid.size());
        case SourceArray::coarse_z: return floats(g.coarse_z);
    }
    return {};
}

std::string absolute_dem_path(const std::string& path) {
    return std::filesystem::absolute(path).lexically_normal().string();
}

std::uint64_t dem_arrays_hash(const DrainageGrid& g) {
    const std::uint64_t z = hash64(g.z.data(), g.z.size() * sizeof(float));
    return hash64(g.coarse_xy.data(), g.coarse_xy.size() * sizeof(glm::vec2), z ^ 0x9e3779b97f4a7c15ull);
}

std::vector<std::uint8_t> assemble_crease_source(const DrainageGrid& g, const CreaseTileIndex& index,
                                                 const std::vector<CodedSourceArray>& arrays, const DemHeightsRef* dem,
                                                 std::uint64_t arrays_hash) {
    if (dem && g.factor != 1)
        throw Error("drainage", "", "a crease source refers to the DEM at factor 1 only", ExitCode::internal);
    std::vector<std::uint8_t> out;
    std::size_t size = 260 + (dem ? dem->path.size() : 0) + 16 * index.lo.size() + 40 * index.units.size() + 4 * index.parts.sources.size() +
                       12 * index.stems.size();
    for (const CodedSourceArray& a : arrays) {
        size += 12 + 4 * a.blocks.size();
        for (const auto& b : a.blocks) size += b.size();
    }
    out.reserve(size);
    put(out, std::uint32_t(g.cols)), put(out, std::uint32_t(g.rows)), put(out, std::int32_t(g.factor));
    put(out, g.dx), put(out, g.dy), put(out, g.origin.x), put(out, g.origin.y);
    put(out, std::int32_t(g.coarse_cols)), put(out, std::int32_t(g.coarse_rows)), put(out, std::uint32_t(g.has_affine));
    put(out, std::uint32_t(coarse_valid_shared(g)));
    put(out, std::uint32_t(dem != nullptr));
    if (dem) {
        put(out, std::uint32_t(dem->path.size()));
        out.insert(out.end(), dem->path.begin(), dem->path.end());
        put(out, std::int32_t(dem->utm_zone)), put(out, std::uint32_t(dem->north)), put(out, arrays_hash);
    }
    for (double v : g.affine.gt) put(out, v);
    put(out, g.affine.unit), put(out, std::int32_t(g.affine.col0)), put(out, std::int32_t(g.affine.row0));
    put(out, std::uint32_t(index.side));
    put(out, std::uint32_t(index.lo.size()));
    put_box(out, index.parts.lo, index.parts.hi);
    for (std::size_t k = 0; k < index.lo.size(); ++k) put_box(out, index.lo[k], index.hi[k]);
    put(out, index.z_top);
    // each unit's stems coded on its own, on all cores
    const std::vector<std::vector<std::uint32_t>> members = crease_unit_stems(index, g.cols, g.rows, g.dx);
    std::vector<std::vector<std::uint8_t>> ids(members.size()), bounds(members.size());
    parallel_chunks(members.size(), 1, [&](std::size_t u0, std::size_t u1) {
        std::vector<StemBound> b;
        for (std::size_t u = u0; u < u1; ++u) {
            b.clear();
            for (std::uint32_t s : members[u]) b.push_back(index.stems[s]);
            ids[u] = encode_stem_ids(members[u].data(), members[u].size()), bounds[u] = encode_stem_bounds(b.data(), b.size());
        }
    });
    put(out, std::uint32_t(index.units.size()));
    for (std::size_t i = 0; i < index.units.size(); ++i) {
        const CreaseUnit& u = index.units[i];
        put(out, u.tile), put(out, u.level), put(out, u.count), put_box(out, u.lo, u.hi);
        put(out, u.most.plan), put(out, u.most.rise), put(out, std::uint32_t(ids[i].size())), put(out, std::uint32_t(bounds[i].size()));
    }
    const std::vector<std::uint32_t>& src = index.parts.sources;
    std::vector<std::uint32_t> deltas(src.size());
    for (std::size_t s = 0; s < src.size(); ++s) deltas[s] = src[s] - (s ? src[s - 1] : 0u);
    put_blocks(out, code_blocks(deltas.size(), [&](std::size_t first, std::size_t k) {
                   return encode_bytes(reinterpret_cast<const std::uint8_t*>(deltas.data() + first), 4 * k);
               }));
    for (std::size_t u = 0; u < members.size(); ++u)
        out.insert(out.end(), ids[u].begin(), ids[u].end()), out.insert(out.end(), bounds[u].begin(), bounds[u].end());
    for (const CodedSourceArray& a : arrays) put_blocks(out, a);
    return out;
}

std::vector<std::uint8_t> encode_crease_source(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                               const CreaseTileIndex& index, const DemHeightsRef* dem) {
    std::vector<CodedSourceArray> arrays;
    for (std::size_t a = 0; a < source_array_count; ++a) {
        const bool referred = dem && (SourceArray(a) == SourceArray::z || SourceArray(a) == SourceArray::coarse_xy);
        arrays.push_back(referred ? CodedSourceArray{} : code_source_array(g, dir, SourceArray(a)));
    }
    return assemble_crease_source(g, index, arrays, dem, dem ? dem_arrays_hash(g) : 0);
}

namespace {

// The fields up to and including the DEM reference: false when they do not read.
struct SourceHead {
    std::uint32_t cols = 0, rows = 0, affine = 0, shared = 0, referred = 0;
    std::int32_t factor = 0, ccols = 0, crows = 0;
    DemHeightsRef dem;
    std::uint64_t arrays_hash = 0;
};

bool get_head(Reader& r, DrainageGrid& g, SourceHead& h) {
    if (!r.get(h.cols) || !r.get(h.rows) || !r.get(h.factor) || !r.get(g.dx) || !r.get(g.dy) || !r.get(g.origin.x) ||
        !r.get(g.origin.y) || !r.get(h.ccols) || !r.get(h.crows) || !r.get(h.affine) || !r.get(h.shared) ||
        !r.get(h.referred) || h.referred > 1)
        return false;
    if (!h.referred) return true;
    std::uint32_t n = 0, north = 0;
    const std::uint8_t* at = nullptr;
    if (!r.get(n) || !r.take(n, at) || !r.get(h.dem.utm_zone) || !r.get(north) || north > 1 || !r.get(h.arrays_hash))
        return false;
    h.dem.path.assign(reinterpret_cast<const char*>(at), n), h.dem.north = north == 1;
    return true;
}

// g.z and g.coarse_xy read again from the DEM `h` refers to (heights only, its zone and
// hemisphere; the grid of a factor-1 build), checked by their hash; false when the DEM cannot be
// read or gives other arrays.
bool read_referred_arrays(const SourceHead& h, DrainageGrid& g) {
    try {
        DemOptions read;
        read.heights_only = true, read.utm_zone = h.dem.utm_zone, read.north = h.dem.north;
        Terrain t = read_dem(h.dem.path, read);
        if (t.cols != g.cols || t.rows != g.rows) return false;
        take_node_arrays(t, g.z, g.coarse_xy);  // resample_pn_releasing(t, 1)'s, without its masks and spacing
    } catch (const Error&) {
        return false;
    }
    return dem_arrays_hash(g) == h.arrays_hash;
}

}  // namespace

std::string crease_source_dem(const CreaseSourceBytes& src) {
    Reader r{src.data, src.size, &src};
    DrainageGrid g;
    SourceHead h;
    return get_head(r, g, h) && h.referred ? h.dem.path : std::string();
}

bool decode_crease_source(const std::uint8_t* data, std::size_t size, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index, SourcePart part, std::vector<SourceUnitBlock>* blocks) {
    return decode_crease_source(CreaseSourceBytes{data, size}, g, dir, index, part, blocks);
}

bool decode_crease_source(const CreaseSourceBytes& src, DrainageGrid& g, std::vector<std::uint8_t>& dir,
                          CreaseTileIndex& index, SourcePart part, std::vector<SourceUnitBlock>* blocks, FlowNetwork* net) {
    const bool arrays = part == SourcePart::all || part == SourcePart::grid,
               stems = part == SourcePart::index || part == SourcePart::all,
               sources = stems || part == SourcePart::sources;
    const std::uint8_t* const data = src.data;
    const std::size_t size = src.size;
    Reader r{data, size, &src};
    std::uint32_t side = 0, tiles = 0;
    std::int32_t col0 = 0, row0 = 0;
    g = DrainageGrid{};
    SourceHead head;
    if (!get_head(r, g, head)) return false;
    const std::uint32_t cols = head.cols, rows = head.rows, affine = head.affine, shared = head.shared;
    const std::int32_t factor = head.factor, ccols = head.ccols, crows = head.crows;
    if (head.referred && factor != 1) return false;
    for (double& v : g.affine.gt)
        if (!r.get(v)) return false;
    if (!r.get(g.affine.unit) || !r.get(col0) || !r.get(row0) || !r.get(side) || !r.get(tiles)) return false;
    if (cols < 2 || rows < 2 || cols > (1u << 30) || rows > (1u << 30) || std::uint64_t(cols) * rows > (1ull << 32) ||
        factor < 1 || ccols < 2 || crows < 2 || std::uint64_t(ccols - 1) * std::uint64_t(factor) + 1 != cols ||
        std::uint64_t(crows - 1) * std::uint64_t(factor) + 1 != rows || affine > 1 || shared > (factor == 1) || side == 0 ||
        side > (1u << 30))
        return false;
    g.cols = int(cols), g.rows = int(rows), g.factor = factor, g.coarse_cols = ccols, g.coarse_rows = crows;
    g.has_affine = affine == 1, g.affine.col0 = col0, g.affine.row0 = row0;
    const std::uint64_t tx = (cols + std::uint64_t(side) - 1) / side, ty = (rows + std::uint64_t(side) - 1) / side;
    if (tiles != tx * ty || r.left / 16 < tiles) return false;
    index.side = int(side);
    if (!get_box(r, index.parts.lo, index.parts.hi)) return false;
    index.lo.resize(tiles), index.hi.resize(tiles);
    for (std::uint32_t k = 0; k < tiles; ++k) get_box(r, index.lo[k], index.hi[k]);
    std::uint32_t units = 0;
    if (!r.get(index.z_top) || !r.get(units) || r.left / 40 < units) return false;
    index.units.resize(units);
    std::vector<SourceUnitBlock> at(units);
    std::uint64_t in_units = 0, unit_bytes = 0;
    for (std::uint32_t i = 0; i < units; ++i) {
        CreaseUnit& u = index.units[i];
        r.get(u.tile), r.get(u.level), r.get(u.count), get_box(r, u.lo, u.hi), r.get(u.most.plan), r.get(u.most.rise);
        r.get(at[i].ids), r.get(at[i].bounds);
        at[i].count = u.count;
        if (u.tile >= tiles || u.level >= std::uint32_t(crease_tile_levels) || u.count == 0 ||
            (i && std::pair(u.tile, u.level) <= std::pair(index.units[i - 1].tile, index.units[i - 1].level)))
            return false;
        at[i].at = unit_bytes, unit_bytes += std::uint64_t(at[i].ids) + at[i].bounds, in_units += u.count;
    }
    const std::size_t n = g.size(), coarse = std::size_t(ccols) * std::size_t(crows);
    std::vector<std::uint32_t>& cells = index.parts.sources;
    if (!get_blocks(
            r, [&](std::uint64_t k) { return k == in_units && k <= n; }, [&](std::size_t k) { cells.resize(sources ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_bytes(c, s, reinterpret_cast<std::uint8_t*>(cells.data() + first), 4 * k);
            },
            sources))
        return false;
    std::uint64_t cell = 0;
    for (std::size_t s = 0; s < cells.size(); ++s) {
        if (s && cells[s] == 0) return false;  // ascending
        cell += cells[s];
        if (cell >= n) return false;
        cells[s] = std::uint32_t(cell);
    }
    auto sized = [](std::size_t want, bool may_be_empty) {
        return [=](std::uint64_t k) { return k == want || (may_be_empty && k == 0); };
    };
    // the units' stems: where they lie; with the index, decoded on all cores and each stem's bound
    // put in its place (every stem in one unit exactly)
    const std::uint8_t* unit_data = r.p;
    if (!(stems ? r.take(std::size_t(unit_bytes), unit_data) : r.skip(std::size_t(unit_bytes)))) return false;
    for (SourceUnitBlock& b : at) b.at += std::uint64_t(unit_data - data);
    if (stems) {
        index.stems.resize(cells.size());
        std::vector<std::uint8_t> ok(units, 0), seen(cells.size(), 0);
        std::vector<std::vector<std::uint32_t>> ids(units);
        std::vector<std::vector<StemBound>> bounds(units);
        parallel_chunks(units, 1, [&](std::size_t u0, std::size_t u1) {
            for (std::size_t u = u0; u < u1; ++u)
                ok[u] = decode_crease_unit(CreaseSourceBytes{data, size}, at[u], ids[u], bounds[u]);  // pages read
        });
        for (std::size_t u = 0; u < units; ++u) {
            if (!ok[u]) return false;
            for (std::size_t i = 0; i < ids[u].size(); ++i) {
                const std::uint32_t s = ids[u][i];
                if (s >= cells.size() || seen[s]) return false;
                seen[s] = 1, index.stems[s] = bounds[u][i];
            }
        }
    }
    if (blocks) *blocks = std::move(at);
    auto floats = [&](std::vector<float>& v, std::size_t want, bool may_be_empty) {
        return get_blocks(
            r, sized(want, may_be_empty), [&](std::size_t k) { v.resize(arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_floats(c, s, v.data() + first, k, z_orders);
            },
            arrays);
    };
    auto bytes = [&](std::vector<std::uint8_t>& v, std::size_t want, bool may_be_empty) {
        return get_blocks(
            r, sized(want, may_be_empty), [&](std::size_t k) { v.resize(arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_bytes(c, s, v.data() + first, k);
            },
            arrays);
    };
    if (!floats(g.z, head.referred ? 0 : n, false) || !bytes(g.valid, n, false) || !bytes(dir, n, false)) return false;
    if (!get_blocks(
            r, sized(head.referred ? 0 : coarse, true), [&](std::size_t k) { g.coarse_xy.resize(arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_floats(c, s, &g.coarse_xy[first].x, k, xy_orders);
            },
            arrays))
        return false;
    if (!bytes(g.coarse_valid, shared ? 0 : coarse, true) || !floats(g.coarse_z, coarse, true)) return false;
    if (shared) g.coarse_valid = g.valid;
    if (r.left != 0) return false;
    if (!(arrays && head.referred)) {
        if (net && arrays) *net = network_of_directions(g, dir);
        return true;
    }
    if (!net) return read_referred_arrays(head, g);
    // the network from the directions and the mask beside the heights and positions read again
    // (which neither reads)
    bool read = false;
    run_beside([&] { *net = network_of_directions(g, dir); }, [&] { read = read_referred_arrays(head, g); });
    return read;
}

bool decode_crease_unit(const CreaseSourceBytes& src, const SourceUnitBlock& block, std::vector<std::uint32_t>& ids,
                        std::vector<StemBound>& bounds) {
    if (block.at > src.size || std::uint64_t(block.ids) + block.bounds > src.size - block.at) return false;
    // deflate packs at most 1032 bytes into one (RFC 1951): the count is bounded by the coded ids
    // before anything is allocated
    if (block.count > (std::uint64_t(block.ids) * 1032 + 1024) / 4) return false;
    src.need(block.at, std::uint64_t(block.ids) + block.bounds);
    ids.resize(block.count), bounds.resize(block.count);
    return decode_stem_ids(src.data + block.at, block.ids, ids.data(), block.count) &&
           decode_stem_bounds(src.data + block.at + block.ids, block.bounds, bounds.data(), block.count);
}

CreaseSourceBytes crease_source_bytes(const std::vector<std::uint8_t>& bytes, const CheckedBlocks* pages,
                                      std::uint64_t size) {
    if (pages) return {static_cast<const std::uint8_t*>(pages->data(0)), std::size_t(size), pages};
    return {bytes.data(), bytes.size(), nullptr};
}

CreaseSourceBytes crease_source_bytes(const DrainageDb& db) {
    return crease_source_bytes(db.crease_source, db.crease_source_pages.get(), db.crease_source_size);
}

void CreaseSourceBytes::need(std::uint64_t at, std::uint64_t n) const {
    if (pages && n) pages->need(0, at, at + n);
}

std::vector<std::uint64_t> crease_source_page_sums(const std::uint8_t* data, std::size_t n) {
    std::vector<std::uint64_t> sums((n + crease_source_page - 1) / crease_source_page);
    parallel_chunks(sums.size(), 64, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k)
            sums[k] = hash64(data + k * crease_source_page, std::min(crease_source_page, n - k * crease_source_page));
    });
    return sums;
}

FlowNetwork network_of_directions(const DrainageGrid& g, const std::vector<std::uint8_t>& dir) {
    FlowNetwork net;
    const GridShape shape{g.cols, g.rows, g.valid.data()};
    run_beside([&] { label_basins(dir, shape, net); }, [&] { accumulate_flow(dir, shape, net); });
    return net;
}

}  // namespace penink
