#include "surface/terrain_cache.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <filesystem>
#include <mutex>
#include <span>
#include <unordered_map>
#include <stdexcept>
#include <vector>

#include <GeographicLib/Constants.hpp>
#include <glm/common.hpp>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/block_codec.hpp"
#include "core/cache_file_write.hpp"
#include "core/checked_blocks.hpp"
#include "core/error.hpp"
#include "core/hash64.hpp"
#include "core/parallel_chunks.hpp"
#include "input/dem_reader.hpp"
#include "input/geographic_nodes.hpp"

namespace penink {

static_assert(std::endian::native == std::endian::little, "terrain caches are written little-endian");

namespace {

constexpr char magic[8] = {'P', 'E', 'N', 'I', 'N', 'K', 'T', 'C'};
constexpr std::uint64_t max_crs_bytes = 1 << 20;
// Elements (nodes, pyramid entries) of one block, coded and checked as one (core/block_codec.hpp,
// core/checked_blocks.hpp): a frame that needs a node reads and decodes its block. 256: the nodes
// are row-major, so a frame that needs the DEM's edge columns (the automatic framing) or a thin
// window reads a block per row and node, not a whole row; the block's size and checksum take 12
// bytes of header (0.15 bytes a node over the three arrays on jacksboro x10), and deflate still
// finds the runs of a block's high byte planes. Caches written with other powers of two, 2^4 to 2^20, are read as well.
constexpr unsigned block_shift = 8;
constexpr unsigned min_block_shift = 4, max_block_shift = 20;

std::uint64_t align_up(std::uint64_t n, std::uint64_t a) { return (n + a - 1) / a * a; }

struct Writer {
    std::vector<std::uint8_t> b;
    template <class T> void put(T v) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
        b.insert(b.end(), p, p + sizeof v);
    }
    void bytes(const void* p, std::size_t n) {
        const auto* q = static_cast<const std::uint8_t*>(p);
        b.insert(b.end(), q, q + n);
    }
};

struct Reader {
    const std::uint8_t* b;
    std::size_t n, at = 0;
    bool ok = true;
    template <class T> T get() {
        T v{};
        if (at + sizeof v > n) {
            ok = false;
            return v;
        }
        std::memcpy(&v, b + at, sizeof v);
        at += sizeof v;
        return v;
    }
};

// The elements of each of the three arrays (positions, valid flags, errors): one a node (the
// padding's errors are not stored).
std::uint64_t node_count(int cols, int rows) { return std::uint64_t(cols) * std::uint64_t(rows); }
std::uint64_t block_count(std::uint64_t elems, unsigned shift) {
    return (elems + (std::uint64_t(1) << shift) - 1) >> shift;
}

// How each array is coded (core/block_codec.hpp): positions x, y differenced twice along a block
// (a grid row's x, y are nearly linear in the column), z once (twice codes jacksboro x10's 7 %
// larger: the heights' second differences are noisier than their first), valid flags deflated as
// they are, errors as they are (neighbouring entries belong to different levels of the pyramid,
// so differences do not shrink them).
constexpr int pos_orders[3] = {2, 2, 1}, z_orders[1] = {1}, error_orders[1] = {0};
// The node lattice (terrain_lod.hpp, LatticeNode): its seven heights differenced once along a
// block (a lattice row's nodes lod_lattice_step apart), the flags and the error as they are.
constexpr int lattice_orders[9] = {1, 1, 1, 1, 1, 1, 1, 0, 0};
static_assert(sizeof(LatticeNode) == 9 * sizeof(float));
// Elements of the node lattice of a cols x rows grid whose x, y are derived (none otherwise).
std::uint64_t lattice_count(int cols, int rows, bool derived) {
    return derived ? std::uint64_t(lattice_size(cols)) * std::uint64_t(lattice_size(rows)) : 0;
}
// The coarse nodes (GridNodes::coarse_step, CoarseNode): heights differenced once along a block
// (a coarse row's nodes grid_coarse_step apart), flags as they are; as many as the lattice's.
constexpr int coarse_orders[2] = {1, 0};
static_assert(sizeof(CoarseNode) == 2 * sizeof(float));
std::uint64_t coarse_count(int cols, int rows, bool derived) {
    const auto n = [](int k) { return std::uint64_t((k - 1) / grid_coarse_step + 1); };
    return derived ? n(cols) * n(rows) : 0;
}
// The edge columns (GridNodes::edges_kept): column 0's nodes, then column cols - 1's, coded as
// the coarse nodes.
std::uint64_t edge_count(int rows, bool derived) { return derived ? 2 * std::uint64_t(rows) : 0; }
// Row r's nodes of the edge columns (heights z, flags v: the row's) into `edges` (2 rows).
void add_edge_row(int cols, int rows, int r, const float* z, const std::uint8_t* v, CoarseNode* edges) {
    edges[r] = {z[0], v[0] ? 1.0f : 0.0f};
    edges[rows + r] = {z[cols - 1], v[cols - 1] ? 1.0f : 0.0f};
}
// The coarse nodes of grid row r (heights z, flags v, cols of each) appended to `out`, when it
// is a coarse row.
void add_coarse_row(int cols, int r, const float* z, const std::uint8_t* v, std::vector<CoarseNode>& out) {
    if (r % grid_coarse_step != 0) return;
    for (int c = 0; c < cols; c += grid_coarse_step) out.push_back({z[c], v[c] ? 1.0f : 0.0f});
}
// Header flags: x, y not stored, the node's x, y given by a formula of the grid: the affine grid
// (a projected DEM), or the projection of the node's longitude, latitude (a geographic DEM).
constexpr std::uint32_t xy_affine = 1, xy_geographic = 2;

// The formula a grid's x, y follow (one of the flags), giving the x, y of a run of nodes.
struct DerivedXY {
    std::uint32_t flag = 0;
    AffineNodes affine;
    std::shared_ptr<const GeographicNodeXY> geographic;
    glm::dvec2 origin{0.0};
    int cols = 0;

    // x, y of nodes c0, c0 + every, ... (< c1) of row r.
    void span(int r, int c0, int c1, int every, glm::vec2* out) const {
        if (geographic) return geographic->span(r, c0, c1, every, out);
        for (int c = c0; c < c1; c += every) out[(c - c0) / every] = affine_node_xy(affine, origin, c, r);
    }
    void span(int r, int c0, int c1, glm::vec2* out) const { span(r, c0, c1, 1, out); }
    // x, y of `count` row-major nodes first, first + every, ..., into the x, y of out (x, y, z each).
    void nodes(std::uint64_t first, std::uint64_t every, std::size_t count, glm::vec3* out) const {
        thread_local std::vector<glm::vec2> xy;
        const std::uint64_t w = std::uint64_t(cols);
        for (std::size_t j = 0; j < count;) {
            const std::uint64_t i = first + j * every;
            const int r = int(i / w), c0 = int(i % w);
            const std::size_t k = std::min<std::uint64_t>(count - j, (w - 1 - std::uint64_t(c0)) / every + 1);  // in row r
            xy.resize(k);
            span(r, c0, int(std::uint64_t(c0) + (k - 1) * every + 1), int(every), xy.data());
            for (std::size_t m = 0; m < k; ++m) out[j + m].x = xy[m].x, out[j + m].y = xy[m].y;
            j += k;
        }
    }
};

// The formula of a grid's x, y (the flag set in `flags`): affine on a projected DEM's grid
// (terrain_affine), the UTM projection of the lon/lat grid on a geographic DEM's
// (terrain_geographic); nullopt when neither applies or fails (a zone that cannot hold the
// lattice, read from a damaged header).
std::optional<DerivedXY> derive_xy(const Terrain& meta, std::uint32_t flags) {
    DerivedXY d;
    d.origin = meta.origin, d.cols = meta.cols;
    GeographicNodes g;
    if ((flags & xy_affine) && terrain_affine(meta, d.affine) && d.affine.col0 == 0 && d.affine.row0 == 0) {
        d.flag = xy_affine;
        return d;
    }
    if ((flags & xy_geographic) && terrain_geographic(meta, g)) {
        try {
            d.geographic = std::make_shared<const GeographicNodeXY>(g, meta.origin);
        } catch (const GeographicLib::GeographicErr&) {
            return std::nullopt;
        }
        d.flag = xy_geographic;
        return d;
    }
    return std::nullopt;
}

// The formula that gives every node's x, y exactly as the nodes hold them (bit for bit): then
// the cache stores z alone. nullopt otherwise (a terrain made otherwise, cropped): x, y stored.
std::optional<DerivedXY> derived_xy(const Terrain& meta, const GridNodes& nodes) {
    const std::optional<DerivedXY> d = derive_xy(meta, xy_affine | xy_geographic);
    if (!d) return std::nullopt;
    std::atomic<bool> exact{true};
    parallel_chunks(std::size_t(nodes.rows), 64, [&](std::size_t r0, std::size_t r1) {
        std::vector<glm::vec2> xy(std::size_t(nodes.cols));
        for (std::size_t r = r0; r < r1 && exact.load(std::memory_order_relaxed); ++r) {
            d->span(int(r), 0, nodes.cols, xy.data());
            for (int c = 0; c < nodes.cols; ++c) {
                const glm::vec3& p = nodes.pos[nodes.index(c, int(r))];
                if (std::bit_cast<std::uint32_t>(xy[std::size_t(c)].x) != std::bit_cast<std::uint32_t>(p.x) ||
                    std::bit_cast<std::uint32_t>(xy[std::size_t(c)].y) != std::bit_cast<std::uint32_t>(p.y)) {
                    exact.store(false, std::memory_order_relaxed);
                    break;
                }
            }
        }
    });
    return exact.load() ? d : std::nullopt;
}

// The coded blocks of one array.
using CodedBlocks = std::vector<std::vector<std::uint8_t>>;
// code(b) of blocks [b0, b0 + count) on every core, then use(b, its bytes) of each in order.
template <class F, class U> void code_batch(std::size_t b0, std::size_t count, F&& code, U&& use) {
    CodedBlocks coded(count);
    parallel_chunks(count, 64, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i) coded[i] = code(b0 + i);
    });
    for (std::size_t i = 0; i < count; ++i) use(b0 + i, std::span<const std::uint8_t>(coded[i]));
}
// code(first element, count) of every block of an array of `elems`, on every core a batch of
// blocks at a time, each batch then handed in order to use(block, its bytes).
template <class F, class U> void code_batches(std::uint64_t elems, F&& code, U&& use) {
    const std::size_t blocks = std::size_t(block_count(elems, block_shift)), batch = 1 << 14;
    for (std::size_t b0 = 0; b0 < blocks; b0 += batch)
        code_batch(b0, std::min(batch, blocks - b0), [&](std::size_t b) {
            const std::uint64_t first = std::uint64_t(b) << block_shift;
            return code(first, std::min<std::uint64_t>(std::uint64_t(1) << block_shift, elems - first));
        }, use);
}
template <class F> CodedBlocks code_blocks(std::uint64_t elems, F&& code) {
    CodedBlocks out(std::size_t(block_count(elems, block_shift)));
    code_batches(elems, code, [&](std::size_t b, std::span<const std::uint8_t> bytes) { out[b].assign(bytes.begin(), bytes.end()); });
    return out;
}

// The coded blocks of an array of `elems` floats whose values come a run at a time, runs in any
// order, each element once: a block is coded when its last element comes (whole blocks of a run
// on every core; the pieces of blocks cut by a run's ends wait, copied, for the rest).
class FloatBlockCoder {
public:
    FloatBlockCoder(std::uint64_t elems, std::span<const int> orders)
        : elems_(elems), orders_(orders), out_(std::size_t(block_count(elems, block_shift))) {
        const std::vector<float> inf(std::size_t(1) << block_shift, std::numeric_limits<float>::infinity());
        inf_block_ = encode_floats(inf.data(), inf.size(), orders_);
    }

    void add(std::uint64_t first, const float* v, std::uint64_t count) {
        const std::uint64_t end = first + count;
        std::uint64_t at = first;
        while (at < end && (at & mask) != 0) at = piece(at, end, v + (at - first));  // a block begun before
        std::uint64_t whole = at;  // whole blocks from `at`
        while (whole < end && block_end(whole) <= end) whole = block_end(whole);
        const std::size_t b0 = std::size_t(at >> block_shift), b1 = b0 + std::size_t((whole - at + mask) >> block_shift);
        parallel_chunks(b1 - b0, 64, [&](std::size_t i0, std::size_t i1) {
            for (std::size_t b = b0 + i0; b < b0 + i1; ++b) {
                const std::uint64_t s = std::uint64_t(b) << block_shift;
                out_[b] = code(v + (s - first), std::size_t(block_end(s) - s));
            }
        });
        for (at = whole; at < end;) at = piece(at, end, v + (at - first));  // a block ended after
    }
    // Block b's bytes (once every element came).
    std::span<const std::uint8_t> block(std::size_t b) const { return out_[b].empty() ? std::span<const std::uint8_t>(inf_block_) : out_[b]; }
    std::size_t blocks() const { return out_.size(); }

private:
    static constexpr std::uint64_t mask = (std::uint64_t(1) << block_shift) - 1;
    struct Partial {
        std::vector<float> v;
        std::uint64_t have = 0;
    };
    std::uint64_t block_end(std::uint64_t i) const { return std::min((i | mask) + 1, elems_); }
    // A whole block of +inf (the padding, most of a long thin DEM's square) is coded once and
    // held once (empty here; block() gives its bytes): the coding is a function of the values,
    // so its bytes are those coding it again would give.
    std::vector<std::uint8_t> code(const float* v, std::size_t count) const {
        const bool inf = count == inf_count && std::all_of(v, v + count, [](float x) {
            return std::bit_cast<std::uint32_t>(x) == std::bit_cast<std::uint32_t>(std::numeric_limits<float>::infinity());
        });
        return inf ? std::vector<std::uint8_t>() : encode_floats(v, count, orders_);
    }
    static constexpr std::size_t inf_count = std::size_t(1) << block_shift;
    // Elements [at, min(end, its block's end)) of a block not whole in the run; returns where they end.
    std::uint64_t piece(std::uint64_t at, std::uint64_t end, const float* v) {
        const std::uint64_t s = at & ~mask, e = std::min(block_end(at), end);
        Partial& p = partial_[s >> block_shift];
        p.v.resize(std::size_t(block_end(s) - s));
        std::copy(v, v + (e - at), p.v.begin() + std::ptrdiff_t(at - s));
        p.have += e - at;
        if (p.have == p.v.size()) {
            out_[std::size_t(s >> block_shift)] = code(p.v.data(), p.v.size());
            partial_.erase(s >> block_shift);
        }
        return e;
    }
    std::uint64_t elems_;
    std::span<const int> orders_;
    CodedBlocks out_;
    std::vector<std::uint8_t> inf_block_;
    std::unordered_map<std::uint64_t, Partial> partial_;
};

struct CodedTerrain {
    CodedBlocks pos, valid, error, lattice, coarse, edges, utm;
    std::uint32_t flags = 0;
};
// The arrays in the order the file holds them.
constexpr int array_count = 7, utm_array = 6;
std::array<const CodedBlocks*, array_count> arrays_of(const CodedTerrain& c) {
    return {&c.pos, &c.valid, &c.error, &c.lattice, &c.coarse, &c.edges, &c.utm};
}
// A geographic grid's UTM lattice (UtmRowProjector::lattice: the exact projections its x, y are
// interpolated from), as it is in memory: what a warm frame would otherwise project again (on
// jacksboro refined 29 times 456 k nodes, about 0.25 s of CPU, the whole of it for a whole view).
CodedBlocks code_utm_lattice(const DerivedXY& d) {
    if (!d.geographic) return {};
    const UtmRowProjector& projector = d.geographic->projector();
    std::vector<glm::dvec2> nodes(projector.lattice_size());
    projector.lattice(nodes.data());
    return code_blocks(nodes.size(), [&](std::uint64_t i, std::uint64_t k) {
        const auto* b = reinterpret_cast<const std::uint8_t*>(nodes.data() + i);
        return std::vector<std::uint8_t>(b, b + k * sizeof(glm::dvec2));
    });
}
CodedBlocks code_coarse_nodes(const std::vector<CoarseNode>& nodes) {
    return code_blocks(nodes.size(), [&](std::uint64_t i, std::uint64_t k) {
        return encode_floats(&nodes[std::size_t(i)].z, std::size_t(k), coarse_orders);
    });
}
CodedBlocks code_lattice(const std::vector<LatticeNode>& lattice) {
    return code_blocks(lattice.size(), [&](std::uint64_t i, std::uint64_t k) {
        return encode_floats(lattice[std::size_t(i)].z, std::size_t(k), lattice_orders);
    });
}
CodedTerrain code_terrain(const StoredTerrain& t) {
    const std::uint64_t nodes = node_count(t.meta.cols, t.meta.rows);
    CodedTerrain c;
    if (const std::optional<DerivedXY> d = derived_xy(t.meta, t.nodes)) {
        c.flags |= d->flag;
        c.pos = code_blocks(nodes, [&](std::uint64_t i, std::uint64_t k) {
            std::vector<float> z(static_cast<std::size_t>(k));
            for (std::size_t j = 0; j < z.size(); ++j) z[j] = t.nodes.pos[i + j].z;
            return encode_floats(z.data(), z.size(), z_orders);
        });
        // each row's heights once into the node lattice, the coarse nodes and the edge columns
        const int cols = t.meta.cols, rows = t.meta.rows;
        std::vector<LatticeNode> lattice(std::size_t(lattice_count(cols, rows, true)));
        std::vector<CoarseNode> coarse, edges(std::size_t(edge_count(rows, true)));
        std::vector<float> z(static_cast<std::size_t>(cols));
        for (int r = 0; r < rows; ++r) {
            const std::size_t at = t.nodes.index(0, r);
            for (std::size_t j = 0; j < z.size(); ++j) z[j] = t.nodes.pos[at + j].z;
            lattice_add_row(cols, rows, r, z.data(), t.nodes.valid + at, lattice.data());
            lattice_add_errors(cols, r, t.lod.error.data() + at, lattice.data());
            add_coarse_row(cols, r, z.data(), t.nodes.valid + at, coarse);
            add_edge_row(cols, rows, r, z.data(), t.nodes.valid + at, edges.data());
        }
        c.lattice = code_lattice(lattice);
        c.coarse = code_coarse_nodes(coarse);
        c.edges = code_coarse_nodes(edges);
        c.utm = code_utm_lattice(*d);
    } else {
        c.pos = code_blocks(nodes, [&](std::uint64_t i, std::uint64_t k) {
            return encode_floats(&t.nodes.pos[i].x, std::size_t(k), pos_orders);
        });
    }
    c.valid = code_blocks(nodes, [&](std::uint64_t i, std::uint64_t k) { return encode_bytes(t.nodes.valid + i, std::size_t(k)); });
    c.error = code_blocks(nodes, [&](std::uint64_t i, std::uint64_t k) {
        return encode_floats(t.lod.error.data() + i, std::size_t(k), error_orders);
    });
    return c;
}

// Each block's coded size and checksum, of the arrays (what the header lists).
struct BlockSums {
    std::vector<std::uint32_t> sizes[array_count];
    std::vector<std::uint64_t> sums[array_count];
    std::uint32_t flags = 0;
    void take(int array, std::size_t b, std::span<const std::uint8_t> bytes) {
        sizes[array][b] = std::uint32_t(bytes.size()), sums[array][b] = hash64(bytes.data(), bytes.size());
    }
};
BlockSums block_sums(const CodedTerrain& coded) {
    BlockSums s;
    s.flags = coded.flags;
    const auto arrays = arrays_of(coded);
    for (int j = 0; j < array_count; ++j) {
        s.sizes[j].resize(arrays[j]->size()), s.sums[j].resize(arrays[j]->size());
        for (std::size_t b = 0; b < arrays[j]->size(); ++b) s.take(j, b, (*arrays[j])[b]);
    }
    return s;
}

// Where the key's identity lies in a header (after the magic, version, length and the key's other
// fields), the one field the header's checksum leaves out (terrain_cache.hpp).
constexpr std::size_t identity_at = 16 + 32;

// hash64 of a header's `n` bytes before its checksum, the identity's 8 left out.
std::uint64_t header_checksum(const std::uint8_t* h, std::size_t n) {
    return hash64(h + identity_at + 8, n - identity_at - 8, hash64(h, identity_at));
}

// The header and the array offsets of `t` (offsets relative to the file's start).
std::vector<std::uint8_t> encode_header(const StoredTerrain& t, const TerrainCacheKey& key, const BlockSums& coded,
                                        std::uint64_t at[array_count], std::uint64_t& total) {
    const Terrain& m = t.meta;
    Writer w;
    w.bytes(magic, 8);
    w.put(terrain_cache_version);
    w.put(std::uint32_t(0));  // header length, set below
    w.put(key.file_size), w.put(key.mtime_ns), w.put(key.content_hash), w.put(key.utm_zone);
    w.put(std::uint32_t(key.north)), w.put(key.identity);
    w.put(std::int32_t(m.cols)), w.put(std::int32_t(m.rows)), w.put(std::int32_t(t.lod.levels));
    w.put(std::uint32_t(m.source_geographic));
    w.put(m.origin.x), w.put(m.origin.y);
    for (double g : m.geotransform) w.put(g);
    w.put(m.xy_unit), w.put(m.elevation_min), w.put(m.elevation_max);
    w.put(std::int32_t(m.utm_zone)), w.put(std::uint32_t(m.north));
    w.put(m.angular_unit), w.put(m.prime_meridian);
    w.put(t.lod.lipschitz), w.put(t.lod.z_min), w.put(t.lod.z_max), w.put(0.0f);
    w.put(t.plan_lo.x), w.put(t.plan_lo.y), w.put(t.plan_hi.x), w.put(t.plan_hi.y);
    const std::size_t offsets = w.b.size();
    for (int i = 0; i <= array_count; ++i) w.put(std::uint64_t(0));
    w.put(std::uint64_t(m.crs_wkt.size()));
    w.bytes(m.crs_wkt.data(), m.crs_wkt.size());
    while (w.b.size() % 8) w.b.push_back(0);
    // the lattice, coarse and edge flags; each block's coded size, then its checksum, the arrays'
    // blocks in turn
    w.put(std::uint32_t(block_shift)), w.put(coded.flags);
    w.put(std::uint32_t(coded.sizes[3].empty() ? 0 : lod_lattice_step));
    w.put(std::uint32_t(coded.sizes[4].empty() ? 0 : grid_coarse_step));
    w.put(std::uint32_t(coded.sizes[5].empty() ? 0 : 1)), w.put(std::uint32_t(coded.sizes[utm_array].empty() ? 0 : 1));
    for (const auto& sizes : coded.sizes) w.bytes(sizes.data(), sizes.size() * sizeof(std::uint32_t));
    while (w.b.size() % 8) w.b.push_back(0);
    for (const auto& sums : coded.sums) w.bytes(sums.data(), sums.size() * sizeof(std::uint64_t));
    const std::uint32_t length = std::uint32_t(w.b.size() + 8);
    std::memcpy(w.b.data() + 12, &length, 4);
    at[0] = length;
    for (int j = 0; j < array_count; ++j) {
        std::uint64_t bytes = 0;
        for (const std::uint32_t n : coded.sizes[j]) bytes += n;
        (j + 1 < array_count ? at[j + 1] : total) = at[j] + bytes;
    }
    std::memcpy(w.b.data() + offsets, at, 8 * array_count);
    std::memcpy(w.b.data() + offsets + 8 * array_count, &total, 8);
    w.put(header_checksum(w.b.data(), w.b.size()));
    return w.b;
}

[[noreturn]] void write_failed(const std::string& path, int err) {
    throw Error("surface", path, std::string("cannot write terrain cache: ") + std::strerror(err));
}

// The file of t's header fields and its coded arrays.
void write_coded(const std::string& path, const StoredTerrain& t, const TerrainCacheKey& key, const CodedTerrain& coded) {
    std::uint64_t at[array_count], total = 0;
    const std::vector<std::uint8_t> header = encode_header(t, key, block_sums(coded), at, total);
    std::vector<std::span<const std::uint8_t>> parts{header};
    for (const CodedBlocks* a : arrays_of(coded))
        for (const auto& b : *a) parts.emplace_back(b);
    if (const int err = write_cache_file(path, parts)) write_failed(path, err);
}

std::optional<StoredTerrain> fail(std::string* why, const std::string& reason) {
    if (why) *why = reason;
    return std::nullopt;
}

}  // namespace

StoredTerrain store_terrain(Terrain flat) {
    if (flat.vertical_exaggeration != 1.0)
        throw std::invalid_argument("terrain cache: the terrain must be read unexaggerated");
    if (flat.pos.size() != flat.size() || flat.valid.size() != flat.size())
        throw std::invalid_argument("terrain cache: terrain positions/valid flags do not match its grid");
    auto owned = std::make_shared<Terrain>(std::move(flat));
    StoredTerrain t;
    t.nodes = grid_nodes(*owned);
    t.lod = build_terrain_lod(t.nodes, 1.0);
    glm::dvec3 lo, hi;
    if (terrain_bounds(*owned, lo, hi)) t.plan_lo = glm::dvec2(lo), t.plan_hi = glm::dvec2(hi);
    t.meta = terrain_metadata(*owned);
    t.in_memory = owned.get();
    t.storage = std::move(owned);
    return t;
}

void write_terrain_cache(const std::string& path, const StoredTerrain& t, const TerrainCacheKey& key) {
    const std::uint64_t nodes = node_count(t.meta.cols, t.meta.rows);
    if (t.lod.error.size() != nodes || t.nodes.size() != t.meta.size())
        throw std::invalid_argument("terrain cache: pyramid and nodes do not match the grid");
    const CodedTerrain coded = code_terrain(t);
    write_coded(path, t, key, coded);
}

namespace {

// The blocks of an array whose elements come in order, a run at a time: coded on every core a
// batch of whole blocks at a time (code_batch), each then handed in order to use(block, bytes);
// finish() codes the last, short block.
template <class T, class Code, class Use> class InOrderBlocks {
public:
    InOrderBlocks(std::uint64_t elems, Code code, Use use) : elems_(elems), code_(std::move(code)), use_(std::move(use)) {}

    void add(const T* v, std::size_t count) {
        pending_.insert(pending_.end(), v, v + count);
        const std::size_t block = std::size_t(1) << block_shift, batch = std::size_t(1) << 14;
        if (pending_.size() >= batch * block) flush(pending_.size() / block);  // the whole blocks
    }
    void finish() {
        const std::size_t block = std::size_t(1) << block_shift;
        flush((pending_.size() + block - 1) / block);
        if (done_ != block_count(elems_, block_shift)) throw std::logic_error("terrain cache: array not whole");
    }

private:
    // Codes the first `blocks` blocks of pending_ (the last may be short) and drops their elements.
    void flush(std::size_t blocks) {
        const std::size_t block = std::size_t(1) << block_shift;
        code_batch(done_, blocks, [&](std::size_t b) {
            const std::size_t at = (b - done_) * block;
            return code_(pending_.data() + at, std::min(block, pending_.size() - at));
        }, use_);
        pending_.erase(pending_.begin(), pending_.begin() + std::ptrdiff_t(std::min(pending_.size(), blocks * block)));
        done_ += blocks;
    }
    std::uint64_t elems_;
    Code code_;
    Use use_;
    std::vector<T> pending_;
    std::size_t done_ = 0;
};

// Thrown out of the pyramid's row loads when a row's x, y are not the formula's.
struct NotFormulaXY {};

}  // namespace

bool build_terrain_cache(const std::string& dem_path, const std::string& path, const TerrainCacheKey& key,
                         const std::function<void(int)>& done, int band_rows) {
    DemRows dem(dem_path, DemOptions{}, band_rows);  // every value checked once: the DEM's errors first
    const Terrain& m = dem.meta();
    const std::optional<DerivedXY> formula = derive_xy(m, xy_affine | xy_geographic);
    if (!formula || m.vertical_exaggeration != 1.0) return false;
    if (done) done(0);

    StoredTerrain t;  // the header's fields
    t.meta = m;  // no arrays
    t.lod.cols = m.cols, t.lod.rows = m.rows;
    t.lod.levels = lod_padded_levels(m.cols, m.rows);
    // The header's length follows the block counts alone: reserved first, written last, the
    // nodes' blocks streamed to the file as they are coded, the flags' held (coded) until the
    // nodes' are written, the pyramid's once all are final.
    const std::uint64_t nodes = node_count(m.cols, m.rows);
    BlockSums sums;
    sums.flags = formula->flag;
    std::vector<LatticeNode> lattice(std::size_t(lattice_count(m.cols, m.rows, true)));  // filled as rows and errors come
    const std::uint64_t coarse_nodes = coarse_count(m.cols, m.rows, true);
    std::vector<CoarseNode> edges(std::size_t(edge_count(m.rows, true)));  // filled as rows come
    const std::size_t utm_nodes = formula->geographic ? formula->geographic->projector().lattice_size() : 0;
    const std::uint64_t counts[array_count] = {block_count(nodes, block_shift), block_count(nodes, block_shift),
                                               block_count(nodes, block_shift), block_count(lattice.size(), block_shift),
                                               block_count(coarse_nodes, block_shift), block_count(edges.size(), block_shift),
                                               block_count(utm_nodes, block_shift)};
    for (int j = 0; j < array_count; ++j)
        sums.sizes[j].assign(std::size_t(counts[j]), 0), sums.sums[j].assign(std::size_t(counts[j]), 0);
    std::uint64_t at[array_count], total = 0;
    const std::size_t head = encode_header(t, key, sums, at, total).size();
    CacheFileStream out(path);
    if (const int err = out.append(std::vector<std::uint8_t>(head, 0))) write_failed(path, err);
    auto code_z = [](const float* v, std::size_t k) { return encode_floats(v, k, z_orders); };
    auto write_z = [&](std::size_t b, std::span<const std::uint8_t> bytes) {
        sums.take(0, b, bytes);
        if (const int err = out.append(bytes)) write_failed(path, err);
    };
    InOrderBlocks<float, decltype(code_z), decltype(write_z)> z_blocks(nodes, code_z, write_z);
    std::vector<std::uint8_t> flags_coded;  // the flags' blocks, back to back
    auto code_valid = [](const std::uint8_t* v, std::size_t k) { return encode_bytes(v, k); };
    auto keep_valid = [&](std::size_t b, std::span<const std::uint8_t> bytes) {
        sums.take(1, b, bytes);
        flags_coded.insert(flags_coded.end(), bytes.begin(), bytes.end());
    };
    InOrderBlocks<std::uint8_t, decltype(code_valid), decltype(keep_valid)> valid_blocks(nodes, code_valid, keep_valid);
    std::vector<std::uint8_t> coarse_coded;  // the coarse nodes' blocks, back to back, written last
    auto code_coarse = [](const CoarseNode* v, std::size_t k) { return encode_floats(&v->z, k, coarse_orders); };
    auto keep_coarse = [&](std::size_t b, std::span<const std::uint8_t> bytes) {
        sums.take(4, b, bytes);
        coarse_coded.insert(coarse_coded.end(), bytes.begin(), bytes.end());
    };
    InOrderBlocks<CoarseNode, decltype(code_coarse), decltype(keep_coarse)> coarse_blocks(coarse_nodes, code_coarse, keep_coarse);
    std::vector<CoarseNode> coarse_row;

    // Rows come once each, in order, as the pyramid's strips ask for them (a window of the rows a
    // strip reads): each row's x, y checked against the formula the cache recomputes them with
    // and reduced to the plan bounds and the Lipschitz bound, its heights and flags coded.
    struct RowSums {
        glm::vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
        float lipschitz2 = 0.0f;
    };
    RowSums all;
    std::mutex merge;
    const std::size_t w = std::size_t(m.cols);
    std::vector<float> win_z;
    std::vector<std::uint8_t> win_valid;
    int win_first = 0, win_end = 0;  // the window holds rows [win_first, win_end)
    auto load = [&](int r0, int r1) {
        if (r0 > win_first) {  // rows before r0 are not read again
            const std::size_t drop = std::size_t(std::min(r0, win_end) - win_first) * w;
            win_z.erase(win_z.begin(), win_z.begin() + std::ptrdiff_t(drop));
            win_valid.erase(win_valid.begin(), win_valid.begin() + std::ptrdiff_t(drop));
            win_first = std::min(r0, win_end);
        }
        if (r1 > win_end) {
            if (win_end < r0) throw std::logic_error("terrain cache: rows skipped");
            const std::size_t old = win_z.size(), k = std::size_t(r1 - win_end);
            win_z.resize(old + k * w), win_valid.resize(old + k * w);
            dem.rows(win_end, r1, win_z.data() + old, win_valid.data() + old);
            std::atomic<bool> exact{true};
            parallel_chunks(k, 4, [&](std::size_t i0, std::size_t i1) {
                std::vector<glm::vec2> xy(w), f(w);
                RowSums sum;
                for (std::size_t i = i0; i < i1 && exact.load(std::memory_order_relaxed); ++i) {
                    const int r = win_end + int(i);
                    dem.xy(r, xy.data());
                    formula->span(r, 0, m.cols, f.data());
                    if (std::memcmp(f.data(), xy.data(), w * sizeof(glm::vec2)) != 0) return exact.store(false);
                    const float* z = win_z.data() + old + i * w;
                    const std::uint8_t* v = win_valid.data() + old + i * w;
                    for (std::size_t c = 0; c < w; ++c) {
                        if (!v[c]) continue;
                        const glm::vec3 p(xy[c].x, xy[c].y, z[c]);
                        sum.lo = glm::min(sum.lo, p), sum.hi = glm::max(sum.hi, p);
                    }
                    if (r + 1 < m.rows) {
                        formula->span(r + 1, 0, m.cols, f.data());
                        sum.lipschitz2 = std::max(sum.lipschitz2, lod_cells_lipschitz2(&xy[0].x, &f[0].x, m.cols, 2));
                    }
                }
                const std::lock_guard<std::mutex> lock(merge);  // min / max: the same in any order
                all.lo = glm::min(all.lo, sum.lo), all.hi = glm::max(all.hi, sum.hi);
                all.lipschitz2 = std::max(all.lipschitz2, sum.lipschitz2);
            });
            if (!exact.load()) throw NotFormulaXY{};
            for (std::size_t i = 0; i < k; ++i) {
                lattice_add_row(m.cols, m.rows, win_end + int(i), win_z.data() + old + i * w,
                                win_valid.data() + old + i * w, lattice.data());
                coarse_row.clear();
                add_coarse_row(m.cols, win_end + int(i), win_z.data() + old + i * w, win_valid.data() + old + i * w, coarse_row);
                coarse_blocks.add(coarse_row.data(), coarse_row.size());
                add_edge_row(m.cols, m.rows, win_end + int(i), win_z.data() + old + i * w, win_valid.data() + old + i * w,
                             edges.data());
            }
            z_blocks.add(win_z.data() + old, k * w);
            valid_blocks.add(win_valid.data() + old, k * w);
            win_end = r1;
        }
        return LodRows{win_z.data() + std::size_t(r0 - win_first) * w, win_valid.data() + std::size_t(r0 - win_first) * w, r0};
    };
    FloatBlockCoder errors(nodes, error_orders);
    const int side = t.lod.side();
    std::vector<float> dem_rows;  // a strip's rows of the DEM, one after the other
    try {
        lod_errors(LodHeights{m.cols, m.rows, nullptr, nullptr, load}, LodStrips{}, [&](int r0, int r1, const float* e) {
            if (r0 >= m.rows) return;  // padding alone
            dem_rows.resize(std::size_t(std::min(r1, m.rows) - r0) * std::size_t(m.cols));
            const int n = lod_dem_rows(m.cols, m.rows, side, r0, r1, e, dem_rows.data());
            for (int i = 0; i < n; ++i) lattice_add_errors(m.cols, r0 + i, dem_rows.data() + std::size_t(i) * w, lattice.data());
            errors.add(std::uint64_t(r0) * std::uint64_t(m.cols), dem_rows.data(), dem_rows.size());
        });
    } catch (const NotFormulaXY&) {
        return false;  // the temporary file removed
    }
    if (win_end != m.rows) throw std::logic_error("terrain cache: rows not read");
    win_z = {}, win_valid = {};
    z_blocks.finish(), valid_blocks.finish(), coarse_blocks.finish();
    if (const int err = out.append(flags_coded)) write_failed(path, err);
    flags_coded = {};
    t.lod.lipschitz = float(std::sqrt(double(all.lipschitz2)));
    if (all.lo.z <= all.hi.z) {
        t.lod.z_min = all.lo.z, t.lod.z_max = all.hi.z;
        t.plan_lo = glm::dvec2(glm::dvec3(all.lo)), t.plan_hi = glm::dvec2(glm::dvec3(all.hi));
    }
    if (done) done(1);
    for (std::size_t b = 0; b < errors.blocks(); ++b) {
        sums.take(2, b, errors.block(b));
        if (const int err = out.append(errors.block(b))) write_failed(path, err);
    }
    const auto write_blocks = [&](int array, const CodedBlocks& blocks) {
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            sums.take(array, b, blocks[b]);
            if (const int err = out.append(blocks[b])) write_failed(path, err);
        }
    };
    write_blocks(3, code_lattice(lattice));
    lattice = {};
    if (const int err = out.append(coarse_coded)) write_failed(path, err);
    write_blocks(5, code_coarse_nodes(edges));
    write_blocks(utm_array, code_utm_lattice(*formula));
    const std::vector<std::uint8_t> header = encode_header(t, key, sums, at, total);
    if (header.size() != head) throw std::logic_error("terrain cache: header length changed");
    if (const int err = out.finish(header)) write_failed(path, err);
    return true;
}

namespace {

// An open cache file (closed with this object).
struct CacheFile {
    int fd = -1;
    explicit CacheFile(int f) : fd(f) {}
    CacheFile(CacheFile&& o) noexcept : fd(o.fd) { o.fd = -1; }
    CacheFile(const CacheFile&) = delete;
    CacheFile& operator=(const CacheFile&) = delete;
    ~CacheFile() {
        if (fd >= 0) ::close(fd);
    }
};

// A header's bytes, not zeroed before they are read (a billion-node DEM's header holds its 25 M
// blocks' sizes and checksums: 295 MB).
struct HeaderBytes {
    std::unique_ptr<std::uint8_t[]> bytes;
    std::size_t size = 0;
};

// The header's length from the first `n` (>= 16) bytes of a cache file of `size` bytes, read
// into `prefix`, checked: the file's size (at least `least_size`), magic, version, length (under
// `least` is damage too); 0 with the reason in *why when any fails.
std::uint32_t header_length(int fd, std::uint64_t size, std::uint8_t* prefix, std::size_t n, std::uint64_t least_size,
                            std::uint32_t least, std::string* why) {
    auto failed = [why](const char* reason) {
        if (why) *why = reason;
        return std::uint32_t(0);
    };
    if (size < least_size || ::pread(fd, prefix, n, 0) != ssize_t(n)) return failed("truncated terrain cache");
    if (std::memcmp(prefix, magic, 8) != 0) return failed("not a terrain cache (bad magic)");
    std::uint32_t version, length;
    std::memcpy(&version, prefix + 8, 4), std::memcpy(&length, prefix + 12, 4);
    if (version != terrain_cache_version) return failed("terrain cache of another version");
    if (length < least || length % 8 || length > size) return failed("damaged terrain cache (header length)");
    return length;
}

// The header of the cache file open as fd (`size` bytes), checked: magic, version, length,
// checksum; empty, with the reason in *why, when any fails.
HeaderBytes checked_header(int fd, std::uint64_t size, std::string* why) {
    auto failed = [why](const char* reason) {
        if (why) *why = reason;
        return HeaderBytes{};
    };
    std::uint8_t prefix[16];
    const std::uint32_t length = header_length(fd, size, prefix, sizeof prefix, 32, 24, why);
    if (length == 0) return {};
    HeaderBytes h{std::unique_ptr<std::uint8_t[]>(new std::uint8_t[length]), length};
    for (std::size_t got = 0; got < length;) {  // a long header may come in several reads
        const ssize_t r = ::pread(fd, h.bytes.get() + got, length - got, off_t(got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return failed("truncated terrain cache");
        got += std::size_t(r);
    }
    std::uint64_t stored = 0;
    std::memcpy(&stored, h.bytes.get() + length - 8, 8);
    if (header_checksum(h.bytes.get(), length - 8) != stored) return failed("damaged terrain cache (header checksum)");
    return h;
}

TerrainCacheKey read_key(Reader& r) {
    TerrainCacheKey k;
    k.file_size = r.get<std::uint64_t>(), k.mtime_ns = r.get<std::int64_t>(), k.content_hash = r.get<std::uint64_t>();
    k.utm_zone = r.get<std::int32_t>(), k.north = r.get<std::uint32_t>() != 0;
    k.identity = r.get<std::uint64_t>();
    return k;
}

// The cache file at `path` opened for reading (a regular file), its size; fd < 0 with the reason
// in *why when it is missing or something else.
CacheFile open_cache(const std::string& path, std::uint64_t& size, std::string* why) {
    // O_NONBLOCK: a FIFO in the cache's place does not block the open (fstat refuses it below)
    CacheFile f(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (f.fd < 0) {
        if (why) *why = "no terrain cache";
        return f;
    }
    struct stat st {};
    if (::fstat(f.fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        if (why) *why = "terrain cache is not a regular file";
        ::close(f.fd), f.fd = -1;
        return f;
    }
    size = std::uint64_t(st.st_size);
    return f;
}

}  // namespace

std::optional<TerrainCacheKey> recorded_terrain_key(const std::string& path) {
    std::uint64_t size = 0;
    const CacheFile f = open_cache(path, size, nullptr);
    if (f.fd < 0) return std::nullopt;
    std::uint8_t head[16 + 40];  // the prefix and the key
    if (header_length(f.fd, size, head, sizeof head, 32 + sizeof head, sizeof head + 8, nullptr) == 0) return std::nullopt;
    Reader r{head, sizeof head, 16};
    return read_key(r);
}

bool record_terrain_identity(const std::string& path, std::uint64_t identity) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) return false;
    const CacheFile f{fd};
    struct stat st {};
    std::uint8_t head[16];
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) ||
        header_length(fd, std::uint64_t(st.st_size), head, sizeof head, identity_at + 8 + 8, identity_at + 16, nullptr) == 0)
        return false;
    return ::pwrite(fd, &identity, 8, off_t(identity_at)) == 8;
}

std::optional<StoredTerrain> read_terrain_cache(const std::string& path, const TerrainCacheKey& key, std::string* why) {
    std::uint64_t size = 0;
    const CacheFile file = open_cache(path, size, why);
    if (file.fd < 0) return std::nullopt;
    const int fd = file.fd;
    // Read, not mapped: a file that shrinks while it is used cannot fault the process.
    const HeaderBytes header = checked_header(fd, size, why);
    if (!header.bytes) return std::nullopt;
    const std::uint32_t length = std::uint32_t(header.size);
    const std::uint8_t* b = header.bytes.get();
    Reader r{b, std::size_t(length) - 8, 16};
    const TerrainCacheKey k = read_key(r);
    if (!(k == key)) return fail(why, "terrain cache is stale (DEM changed)");
    StoredTerrain t;
    Terrain& m = t.meta;
    m.cols = r.get<std::int32_t>(), m.rows = r.get<std::int32_t>();
    const int levels = r.get<std::int32_t>();
    m.source_geographic = r.get<std::uint32_t>() != 0;
    m.origin.x = r.get<double>(), m.origin.y = r.get<double>();
    for (double& g : m.geotransform) g = r.get<double>();
    m.xy_unit = r.get<double>(), m.elevation_min = r.get<double>(), m.elevation_max = r.get<double>();
    m.utm_zone = r.get<std::int32_t>(), m.north = r.get<std::uint32_t>() != 0;
    m.angular_unit = r.get<double>(), m.prime_meridian = r.get<double>();
    t.lod.lipschitz = r.get<float>(), t.lod.z_min = r.get<float>(), t.lod.z_max = r.get<float>();
    r.get<float>();
    t.plan_lo.x = r.get<double>(), t.plan_lo.y = r.get<double>(), t.plan_hi.x = r.get<double>(), t.plan_hi.y = r.get<double>();
    std::uint64_t at[array_count];
    for (std::uint64_t& a : at) a = r.get<std::uint64_t>();
    const std::uint64_t total = r.get<std::uint64_t>(), crs = r.get<std::uint64_t>();
    if (!r.ok || crs > max_crs_bytes || crs > r.n - r.at) return fail(why, "damaged terrain cache (header)");
    m.crs_wkt.assign(reinterpret_cast<const char*>(b + r.at), std::size_t(crs));
    r.at = std::size_t(align_up(r.at + crs, 8));
    if (m.cols < 2 || m.rows < 2 || std::max(m.cols, m.rows) > (1 << 30) || levels != lod_padded_levels(m.cols, m.rows))
        return fail(why, "damaged terrain cache (grid)");
    const std::uint64_t nodes = node_count(m.cols, m.rows);
    bool ordered = total == size && at[0] >= length && total >= at[array_count - 1];
    for (int j = 1; j < array_count; ++j) ordered = ordered && at[j] >= at[j - 1];
    if (!ordered) return fail(why, "damaged terrain cache (lengths)");
    const std::uint32_t shift = r.get<std::uint32_t>(), flags = r.get<std::uint32_t>();
    const std::uint32_t step = r.get<std::uint32_t>(), coarse_step = r.get<std::uint32_t>();
    const std::uint32_t edges = r.get<std::uint32_t>(), utm = r.get<std::uint32_t>();
    if (!r.ok || shift < min_block_shift || shift > max_block_shift || (flags & ~(xy_affine | xy_geographic)) != 0 ||
        flags == (xy_affine | xy_geographic) || (step != 0 && (step != std::uint32_t(lod_lattice_step) || !flags)) ||
        (coarse_step != 0 && (coarse_step != std::uint32_t(grid_coarse_step) || !flags)) || edges > 1 ||
        (edges && !flags) || utm > 1 || (utm && flags != xy_geographic))
        return fail(why, "damaged terrain cache (block checksums)");
    // (the grid's formula: a geographic one's lattice size for the UTM lattice's count)
    const std::optional<DerivedXY> derived = flags ? derive_xy(m, flags) : std::nullopt;
    if (flags && !derived) return fail(why, "damaged terrain cache (grid)");
    const std::uint64_t utm_nodes = utm ? derived->geographic->projector().lattice_size() : 0;
    const std::uint64_t lattice = lattice_count(m.cols, m.rows, step != 0);
    const std::uint64_t coarse = coarse_count(m.cols, m.rows, coarse_step != 0);
    const std::uint64_t edge_nodes = edge_count(m.rows, edges != 0);
    const std::uint64_t counts[array_count] = {block_count(nodes, shift),      block_count(nodes, shift),
                                               block_count(nodes, shift),      block_count(lattice, shift),
                                               block_count(coarse, shift),     block_count(edge_nodes, shift),
                                               block_count(utm_nodes, shift)};
    std::uint64_t blocks = 0;
    for (const std::uint64_t n : counts) blocks += n;
    if (align_up(blocks * 4, 8) + blocks * 8 != r.n - r.at) return fail(why, "damaged terrain cache (block checksums)");
    std::vector<CheckedBlocks::CodedArray> arrays(array_count);
    const std::uint8_t* sizes = b + r.at;
    for (int j = 0; j < array_count; ++j) {
        CheckedBlocks::CodedArray& a = arrays[std::size_t(j)];
        a.offset = at[j], a.shift = shift;
        // 4-byte aligned: the header is allocated aligned and its tables start at a multiple of 8
        a.sizes = std::span<const std::uint32_t>(reinterpret_cast<const std::uint32_t*>(sizes), std::size_t(counts[j]));
        sizes += counts[j] * 4;
        std::uint64_t coded = 0;
        for (const std::uint32_t c : a.sizes) coded += c;
        if (at[j] + coded != (j + 1 < array_count ? at[j + 1] : total)) return fail(why, "damaged terrain cache (lengths)");
    }
    arrays[0].elems = nodes, arrays[0].elem_bytes = sizeof(glm::vec3);
    if (flags) {
        arrays[0].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
            thread_local std::vector<float> z;
            z.resize(count);
            if (!decode_floats(c, bytes, z.data(), count, z_orders)) return false;
            auto* p = static_cast<glm::vec3*>(out);
            for (std::size_t j = 0; j < count; ++j) p[j].z = z[j];
            return true;
        };
        arrays[0].derive = [d = *derived](void* out, std::uint64_t first, std::uint64_t every, std::size_t count) {
            d.nodes(first, every, count, static_cast<glm::vec3*>(out));
        };
    } else {
        arrays[0].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
            return decode_floats(c, bytes, static_cast<float*>(out), count, pos_orders);
        };
    }
    arrays[1].elems = nodes, arrays[1].elem_bytes = 1;
    arrays[1].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
        return decode_bytes(c, bytes, static_cast<std::uint8_t*>(out), count);
    };
    {  // a block of valid nodes alone as the writer codes it (code_terrain): known without reading it
        const std::vector<std::uint8_t> ones(std::size_t(1) << shift, 1);
        const std::vector<std::uint8_t> coded = encode_bytes(ones.data(), ones.size());
        arrays[1].fill_size = std::uint32_t(coded.size()), arrays[1].fill_sum = hash64(coded.data(), coded.size());
        arrays[1].fill_byte = 1;
    }
    arrays[2].elems = nodes, arrays[2].elem_bytes = sizeof(float);
    arrays[2].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
        return decode_floats(c, bytes, static_cast<float*>(out), count, error_orders);
    };
    arrays[3].elems = lattice, arrays[3].elem_bytes = sizeof(LatticeNode);
    arrays[3].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
        return decode_floats(c, bytes, static_cast<float*>(out), count, lattice_orders);
    };
    arrays[4].elems = coarse, arrays[4].elem_bytes = sizeof(CoarseNode);
    arrays[4].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
        return decode_floats(c, bytes, static_cast<float*>(out), count, coarse_orders);
    };
    arrays[5].elems = edge_nodes, arrays[5].elem_bytes = sizeof(CoarseNode);
    arrays[5].decode = arrays[4].decode;
    arrays[utm_array].elems = utm_nodes, arrays[utm_array].elem_bytes = sizeof(glm::dvec2);
    arrays[utm_array].decode = [](const std::uint8_t* c, std::size_t bytes, void* out, std::uint64_t, std::size_t count) {
        if (bytes != count * sizeof(glm::dvec2)) return false;  // as in memory
        std::memcpy(out, c, bytes);
        return true;
    };
    const auto* stored_sums = reinterpret_cast<const std::uint64_t*>(b + r.at + align_up(blocks * 4, 8));  // 8-aligned
    std::vector<std::uint64_t> sums(stored_sums, stored_sums + blocks);
    std::shared_ptr<CheckedBlocks> coded;
    try {
        coded = std::make_shared<CheckedBlocks>(fd, path, std::move(arrays), std::move(sums));
    } catch (const std::bad_alloc&) {
        return fail(why, "terrain cache too large for memory");
    }
    if (utm_nodes) {  // the projection's lattice read into place as the build projected it: not projected again
        try {
            derived->geographic->projector().adopt_lattice(
                [&](glm::dvec2* into) { coded->read_strided(utm_array, 0, utm_nodes, 1, into); });
        } catch (const DamagedBlockError&) {
            return fail(why, "damaged terrain cache (UTM lattice)");
        }
    }
    static_assert(GridNodes::pos_array == 0 && GridNodes::valid_array == 1 && TerrainLod::error_array == 2 &&
                  TerrainLod::lattice_array == 3 && GridNodes::coarse_array == 4 && GridNodes::edge_array == 5);
    t.nodes.cols = m.cols, t.nodes.rows = m.rows;
    t.nodes.pos = static_cast<const glm::vec3*>(coded->data(GridNodes::pos_array));
    t.nodes.valid = static_cast<const std::uint8_t*>(coded->data(GridNodes::valid_array));
    t.nodes.blocks = coded.get();
    t.nodes.coarse_step = int(coarse_step);
    t.nodes.edges_kept = edges != 0;
    t.lod.cols = m.cols, t.lod.rows = m.rows, t.lod.levels = levels;
    t.lod.error = std::span<const float>(static_cast<const float*>(coded->data(TerrainLod::error_array)),
                                         std::size_t(nodes));
    t.lod.blocks = coded.get();
    t.lod.lattice_step = int(step);
    t.lod.storage = coded;
    t.storage = std::move(coded);
    return t;
}

void read_whole(const StoredTerrain& t) {
    t.nodes.need(GridWindow{0, 0, t.nodes.cols, t.nodes.rows});
    if (t.lod.blocks) t.lod.blocks->need(TerrainLod::error_array, 0, t.lod.error.size());
    if (t.lod.blocks && t.lod.lattice_step)
        t.lod.blocks->need(TerrainLod::lattice_array, 0, lattice_count(t.lod.cols, t.lod.rows, true));
    if (t.nodes.blocks && t.nodes.coarse_step)
        t.nodes.blocks->need(GridNodes::coarse_array, 0, coarse_count(t.nodes.cols, t.nodes.rows, true));
    if (t.nodes.blocks && t.nodes.edges_kept) t.nodes.blocks->need(GridNodes::edge_array, 0, edge_count(t.nodes.rows, true));
}

}  // namespace penink
