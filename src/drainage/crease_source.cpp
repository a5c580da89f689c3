#include "drainage/crease_source.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <filesystem>

#include <GeographicLib/Constants.hpp>

#include "core/big_allocator.hpp"
#include "core/block_codec.hpp"
#include "core/error.hpp"
#include "core/hash64.hpp"
#include "core/parallel_chunks.hpp"
#include "input/dem_reader.hpp"
#include "input/geographic_nodes.hpp"

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

constexpr std::array<int, 3> network_orders{0, 0, 0};  // a cell's accumulation, basin, order residuals
constexpr std::array<int, 1> totals_orders{0};

// The flow inside block b of `grid`: each cell's downstream cell where that lies in the block (its
// place in the block's order; -1 where it drains out of it, or is an outlet or invalid).
void block_downstream(const BlockGrid& grid, std::size_t b, const GridShape& shape, const std::uint8_t* dir,
                      std::vector<std::int32_t>& down) {
    std::size_t c0, c1, r0, r1;
    grid.span(b, c0, c1, r0, r1);
    down.assign(grid.cells(b), -1);
    grid.each_cell(b, [&](std::size_t i, std::size_t k) {
        if (!shape.valid[i] || !dir[i]) return;
        const std::size_t d = d8_target(shape, i, dir[i]), dc = d % grid.cols, dr = d / grid.cols;
        if (dc >= c0 && dc < c1 && dr >= r0 && dr < r1) down[k] = std::int32_t((dr - r0) * (c1 - c0) + (dc - c0));
    });
}

// A block's cells' network as predicted from the flow inside it (the stored residuals are the
// differences, which vanish but where flow enters from outside or leaves it): a valid cell's
// accumulation 1 + the accumulations of the cells draining into it in the block, its Strahler
// order from theirs (push_order, final_order), its basin its downstream cell's in the block
// (else 0); 0, 0, 0 for an invalid cell.
struct BlockPrediction {
    std::vector<std::uint32_t> acc;
    std::vector<std::uint8_t> pending, valid;
    void start(const BlockGrid& grid, std::size_t b, const GridShape& shape) {
        acc.resize(grid.cells(b)), pending.assign(grid.cells(b), 0), valid.resize(grid.cells(b));
        grid.each_cell(b, [&](std::size_t i, std::size_t k) {
            valid[k] = shape.valid[i] != 0;
            acc[k] = valid[k];
        });
    }
    // cell k's true accumulation and order are known: passed on to its downstream cell
    void pass(std::int32_t down, std::uint32_t a, std::uint8_t o) {
        if (down < 0) return;
        acc[std::size_t(down)] += a;
        push_order(pending[std::size_t(down)], o);
    }
    std::uint8_t order(std::size_t k) const { return valid[k] ? final_order(pending[k]) : 0; }
};

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

CodedSourceNetwork code_source_network(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                       const FlowNetwork& net, int side) {
    const std::size_t n = g.size();
    if (side < 1 || side > (1 << 15)) throw Error("drainage", "", "network block side out of range", ExitCode::internal);
    if (dir.size() != n || net.acc.size() != n || net.basin.size() != n || net.order.size() != n ||
        net.mains.size() != mains_words(n))
        throw Error("drainage", "", "network stored without its directions, accumulation, basins, orders or mains",
                    ExitCode::internal);
    CodedSourceNetwork out;
    out.side = side, out.basins = net.outlet.size();
    std::vector<float> totals(net.outlet.size());
    for (std::size_t b = 0; b < totals.size(); ++b) totals[b] = std::bit_cast<float>(net.acc[net.outlet[b]]);
    out.totals = encode_floats(totals.data(), totals.size(), totals_orders);
    const auto* words = reinterpret_cast<const std::uint8_t*>(net.mains.data());
    out.mains = code_blocks(8 * net.mains.size(), [&](std::size_t first, std::size_t k) { return encode_bytes(words + first, k); });
    const BlockGrid grid(std::size_t(g.cols), std::size_t(g.rows), std::size_t(side));
    const GridShape shape{g.cols, g.rows, g.valid.data()};
    out.blocks.resize(grid.count());
    parallel_chunks(grid.count(), 1, [&](std::size_t b0, std::size_t b1) {
        std::vector<float> cells;
        std::vector<std::int32_t> down;
        std::vector<std::uint32_t> at;  // the block's cells
        BlockPrediction p;
        for (std::size_t b = b0; b < b1; ++b) {
            block_downstream(grid, b, shape, dir.data(), down);
            p.start(grid, b, shape);
            at.resize(grid.cells(b));
            grid.each_cell(b, [&](std::size_t i, std::size_t k) {
                at[k] = std::uint32_t(i);
                p.pass(down[k], net.acc[i], net.order[i]);
            });
            cells.resize(3 * at.size());
            for (std::size_t k = 0; k < at.size(); ++k) {
                const std::size_t i = at[k];
                const std::uint32_t basin_below = down[k] < 0 ? 0u : net.basin[at[std::size_t(down[k])]];
                cells[3 * k] = std::bit_cast<float>(net.acc[i] - p.acc[k]);
                cells[3 * k + 1] = std::bit_cast<float>(net.basin[i] - basin_below);
                cells[3 * k + 2] = std::bit_cast<float>(std::uint32_t(net.order[i]) - p.order(k));
            }
            out.blocks[b] = encode_floats(cells.data(), at.size(), network_orders);
            out.blocks[b].shrink_to_fit();
        }
    });
    return out;
}

std::string absolute_dem_path(const std::string& path) {
    return std::filesystem::absolute(path).lexically_normal().string();
}

namespace {

// hash64 of block b of an array over `grid`'s cells (its values at v), row by row.
template <class T> std::uint64_t block_hash(const T* v, const BlockGrid& grid, std::size_t b) {
    std::size_t c0, c1, r0, r1;
    grid.span(b, c0, c1, r0, r1);
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::size_t r = r0; r < r1; ++r) h = hash64(v + r * grid.cols + c0, (c1 - c0) * sizeof(T), h);
    return h;
}

// block_hash of every block of `v` (over `grid`'s cells), on all cores.
template <class T> std::vector<std::uint64_t> block_hashes(const T* v, const BlockGrid& grid) {
    std::vector<std::uint64_t> out(grid.count());
    parallel_chunks(grid.count(), 16, [&](std::size_t b0, std::size_t b1) {
        for (std::size_t b = b0; b < b1; ++b) out[b] = block_hash(v, grid, b);
    });
    return out;
}

}  // namespace

DemArraysHash dem_arrays_hash(const DrainageGrid& g) {
    DemArraysHash out;
    if (g.z.size() != g.size() || g.size() == 0) return out;
    const BlockGrid grid(std::size_t(g.cols), std::size_t(g.rows), network_block_side);
    out.z = block_hashes(g.z.data(), grid);
    if (g.coarse_xy.size() == g.size()) out.xy = block_hashes(g.coarse_xy.data(), grid);
    return out;
}

std::vector<std::uint8_t> assemble_crease_source(const DrainageGrid& g, const CodedCreaseIndex& coded,
                                                 const std::vector<CodedSourceArray>& arrays, const DemHeightsRef* dem,
                                                 const DemArraysHash& hashes, const CodedSourceNetwork* network) {
    const CreaseTileIndex& index = coded.index;
    const std::vector<std::vector<std::uint8_t>>&ids = coded.ids, &bounds = coded.bounds;
    if (ids.size() != index.units.size() || bounds.size() != index.units.size())
        throw Error("drainage", "", "crease index coded for other units", ExitCode::internal);
    if (dem && g.factor != 1)
        throw Error("drainage", "", "a crease source refers to the DEM at factor 1 only", ExitCode::internal);
    std::vector<std::uint8_t> out;
    std::size_t size = 260 + (dem ? dem->path.size() + 8 * (hashes.z.size() + hashes.xy.size()) : 0) + 16 * index.lo.size() +
                       40 * index.units.size() + 4 * index.parts.sources.size();
    for (std::size_t u = 0; u < ids.size(); ++u) size += ids[u].size() + bounds[u].size();
    for (const CodedSourceArray& a : arrays) {
        size += 12 + 4 * a.blocks.size();
        for (const auto& b : a.blocks) size += b.size();
    }
    if (network) {
        size += 32 + network->totals.size() + 4 * network->mains.blocks.size() + 4 * network->blocks.size();
        for (const auto& b : network->mains.blocks) size += b.size();
        for (const auto& b : network->blocks) size += b.size();
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
        put(out, std::int32_t(dem->utm_zone)), put(out, std::uint32_t(dem->north));
        for (const auto* v : {&hashes.z, &hashes.xy}) {
            put(out, std::uint32_t(v->size()));
            for (std::uint64_t h : *v) put(out, h);
        }
    }
    for (double v : g.affine.gt) put(out, v);
    put(out, g.affine.unit), put(out, std::int32_t(g.affine.col0)), put(out, std::int32_t(g.affine.row0));
    put(out, std::uint32_t(index.side));
    put(out, std::uint32_t(index.lo.size()));
    put_box(out, index.parts.lo, index.parts.hi);
    for (std::size_t k = 0; k < index.lo.size(); ++k) put_box(out, index.lo[k], index.hi[k]);
    put(out, index.z_top);
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
    for (std::size_t u = 0; u < ids.size(); ++u)
        out.insert(out.end(), ids[u].begin(), ids[u].end()), out.insert(out.end(), bounds[u].begin(), bounds[u].end());
    for (const CodedSourceArray& a : arrays) put_blocks(out, a);
    put(out, std::uint32_t(network != nullptr));
    if (network) {
        put(out, std::uint32_t(network->side)), put(out, network->basins);
        put(out, std::uint32_t(network->totals.size()));
        out.insert(out.end(), network->totals.begin(), network->totals.end());
        put_blocks(out, network->mains);
        put(out, std::uint32_t(network->blocks.size()));
        for (const auto& b : network->blocks) put(out, std::uint32_t(b.size()));
        for (const auto& b : network->blocks) out.insert(out.end(), b.begin(), b.end());
    }
    return out;
}

std::vector<std::uint8_t> encode_crease_source(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                               const CreaseTileIndex& index, const DemHeightsRef* dem,
                                               const FlowNetwork* network, int network_side) {
    std::vector<CodedSourceArray> arrays;
    for (std::size_t a = 0; a < source_array_count; ++a) {
        const bool referred = dem && (SourceArray(a) == SourceArray::z || SourceArray(a) == SourceArray::coarse_xy);
        arrays.push_back(referred ? CodedSourceArray{} : code_source_array(g, dir, SourceArray(a)));
    }
    const CodedSourceNetwork coded = network ? code_source_network(g, dir, *network, network_side) : CodedSourceNetwork{};
    return assemble_crease_source(g, code_crease_index(index, g.cols, g.rows, g.dx), arrays, dem,
                                  dem ? dem_arrays_hash(g) : DemArraysHash{}, network ? &coded : nullptr);
}

namespace {

// The fields up to and including the DEM reference: false when they do not read.
struct SourceHead {
    std::uint32_t cols = 0, rows = 0, affine = 0, shared = 0, referred = 0;
    std::int32_t factor = 0, ccols = 0, crows = 0;
    DemHeightsRef dem;
    DemArraysHash hashes;
};

bool get_head(Reader& r, DrainageGrid& g, SourceHead& h) {
    if (!r.get(h.cols) || !r.get(h.rows) || !r.get(h.factor) || !r.get(g.dx) || !r.get(g.dy) || !r.get(g.origin.x) ||
        !r.get(g.origin.y) || !r.get(h.ccols) || !r.get(h.crows) || !r.get(h.affine) || !r.get(h.shared) ||
        !r.get(h.referred) || h.referred > 1)
        return false;
    if (!h.referred) return true;
    std::uint32_t n = 0, north = 0;
    const std::uint8_t* at = nullptr;
    if (!r.get(n) || !r.take(n, at) || !r.get(h.dem.utm_zone) || !r.get(north) || north > 1) return false;
    h.dem.path.assign(reinterpret_cast<const char*>(at), n), h.dem.north = north == 1;
    for (auto* v : {&h.hashes.z, &h.hashes.xy}) {
        std::uint32_t blocks = 0;
        if (!r.get(blocks) || blocks > r.left / 8) return false;
        v->resize(blocks);
        for (std::uint64_t& x : *v) r.get(x);
    }
    return true;
}

// g.z and g.coarse_xy read again from the DEM `h` refers to (heights only, its zone and
// hemisphere; the grid of a factor-1 build), checked by their hashes; false when the DEM cannot be
// read or gives other arrays.
// With `by_blocks`, a geographic DEM's x, y made by blocks where read (DrainageGrid::node_blocks,
// GeographicNodeXY), and the heights read by blocks through `heights` where given (the DEM opened
// for its georeference alone), else read whole; each block checked by its hashes as it is made
// (throwing penink::Error(internal) where one differs). A geographic DEM whose x, y the formula
// does not make is read whole.
bool read_referred_arrays(const SourceHead& h, DrainageGrid& g, bool by_blocks = false,
                          const NodeHeights* heights = nullptr) {
    const std::size_t n = g.size();
    const BlockGrid grid(std::size_t(g.cols), std::size_t(g.rows), network_block_side);
    if (h.hashes.z.size() != grid.count()) return false;
    try {
        DemOptions read;
        read.heights_only = true, read.utm_zone = h.dem.utm_zone, read.north = h.dem.north;
        const auto whole = [&] {
            Terrain t = read_dem(h.dem.path, read);
            if (t.cols != g.cols || t.rows != g.rows) return false;
            take_node_arrays(t, g.z, g.coarse_xy);  // resample_pn_releasing(t, 1)'s, without its masks and spacing
            return dem_arrays_hash(g) == h.hashes;
        };
        if (!by_blocks) return whole();
        const bool z_blocks = heights && heights->span && heights->cols == g.cols && heights->rows == g.rows;
        Terrain t;
        if (z_blocks) t = DemRows(h.dem.path, read, 0, false).meta();
        else read.no_xy = true, t = read_dem(h.dem.path, read);
        GeographicNodes geo;
        const bool formula = terrain_geographic(t, geo);
        if (!formula && !h.hashes.xy.empty()) return read.no_xy = false, whole();  // x, y read with the heights
        if (t.cols != g.cols || t.rows != g.rows || (formula && h.hashes.xy.size() != grid.count())) return false;
        if (z_blocks) {
            g.z.clear();
            // not written: the pages of the blocks never read are never touched; nor advised for
            // huge pages, which malloc's (glibc.malloc.hugetlb) were: each block read then faulted
            // and zeroed the 2 MiB pages its rows cross, 64 of them (a new view of jacksboro x29:
            // a quarter of its CPU in page faults)
            float* z = static_cast<float*>(allocate_big(n * sizeof(float)));
            advise_small_pages(z, n * sizeof(float));
            g.block_z = std::shared_ptr<float[]>(z, [n](float* p) { deallocate_big(p, n * sizeof(float)); });
        } else {
            take_node_heights(t, g.z);
            if (block_hashes(g.z.data(), grid) != h.hashes.z) return false;
        }
        if (formula) {
            g.node_xy = std::make_shared<const GeographicNodeXY>(geo, t.origin);
            g.coarse_xy.resize(n);  // (not written: the pages of the blocks never made are never touched)
            advise_small_pages(g.coarse_xy.data(), n * sizeof(glm::vec2));
        }
        if (!z_blocks && !formula) return true;  // an affine grid's heights read whole (no x, y stored)
        g.node_blocks = std::make_shared<CellBlocks>(
            grid, [grid, sums = h.hashes, span = z_blocks ? heights->span : nullptr, nodes = g.node_xy, heights_kept = g.block_z,
                   xy = formula ? g.coarse_xy.data() : nullptr, path = h.dem.path](std::size_t b) {
                std::size_t c0, c1, r0, r1;
                grid.span(b, c0, c1, r0, r1);
                float* const z = heights_kept.get();
                for (std::size_t r = r0; r < r1; ++r) {
                    if (span) span(int(r), int(c0), int(c1), z + r * grid.cols + c0);
                    if (xy) nodes->span(int(r), int(c0), int(c1), xy + r * grid.cols + c0);
                }
                if ((span && block_hash(z, grid, b) != sums.z[b]) || (xy && block_hash(xy, grid, b) != sums.xy[b]))
                    throw Error("drainage", path, "the DEM's heights or node positions differ from its drainage database's",
                                ExitCode::internal);
            });
    } catch (const Error&) {
        return false;
    } catch (const GeographicLib::GeographicErr&) {  // the build projected it: cannot happen
        return false;
    }
    return true;
}

// Where a source stores its network (code_source_network), read up to its blocks.
struct StoredNetworkAt {
    std::uint32_t side = 0;
    std::uint64_t basins = 0;
    const std::uint8_t* totals = nullptr;
    std::uint32_t totals_size = 0;
    std::vector<std::uint64_t> mains;
    std::vector<std::uint64_t> at;  // each block's offset in the source's bytes
    std::vector<std::uint32_t> sizes;
};

// Reads what assemble_crease_source wrote of a network on a grid of cols x rows (n cells):
// `stored` set when there is one; its totals and mains taken and its blocks found when `want`,
// else passed over. False when the bytes do not read so.
bool get_network(Reader& r, const std::uint8_t* data, std::size_t cols, std::size_t rows, bool want, bool& stored,
                 StoredNetworkAt& out) {
    std::uint32_t has = 0;
    if (!r.get(has) || has > 1) return false;
    stored = has == 1;
    if (!stored) return true;
    const std::size_t n = cols * rows;
    if (!r.get(out.side) || out.side == 0 || out.side > (1u << 15) || !r.get(out.basins) || out.basins > n ||
        !r.get(out.totals_size) || !(want ? r.take(out.totals_size, out.totals) : r.skip(out.totals_size)))
        return false;
    const std::size_t words = mains_words(n);
    if (!get_blocks(
            r, [&](std::uint64_t k) { return k == 8 * words; }, [&](std::size_t) { out.mains.resize(want ? words : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_bytes(c, s, reinterpret_cast<std::uint8_t*>(out.mains.data()) + first, k);
            },
            want))
        return false;
    const BlockGrid grid(cols, rows, out.side);
    std::uint32_t count = 0;
    if (!r.get(count) || count != grid.count() || r.left / 4 < count) return false;
    out.sizes.resize(count), out.at.resize(count);
    for (auto& v : out.sizes) r.get(v);
    for (std::uint32_t b = 0; b < count; ++b) {
        out.at[b] = std::uint64_t(r.p - data);
        if (!r.skip(out.sizes[b])) return false;
    }
    return true;
}

// Block b of a stored network decoded: its cells' accumulation, basin and order (`acc`, `basin`,
// `order`, in the block's order), the residuals added to the predictions from the flow inside it
// in its cells' topological order (upstream first; the basins downstream first). False when it does
// not decode, its flow inside holds a cycle or a basin exceeds the basins stored.
struct DecodedBlock {
    std::vector<float> cells;
    std::vector<std::int32_t> down;
    std::vector<std::uint32_t> acc, basin, topo;
    std::vector<std::uint8_t> order, inflows;
    BlockPrediction p;
};
bool decode_network_block(const CreaseSourceBytes& src, const BlockGrid& grid, const StoredNetworkAt& at,
                          const GridShape& shape, const std::uint8_t* dir, std::size_t b, DecodedBlock& d) {
    const std::size_t n = grid.cells(b);
    src.need(at.at[b], at.sizes[b]);
    d.cells.resize(3 * n);
    if (!decode_floats(src.data + at.at[b], at.sizes[b], d.cells.data(), n, network_orders)) return false;
    block_downstream(grid, b, shape, dir, d.down);
    d.p.start(grid, b, shape);
    d.inflows.assign(n, 0), d.topo.clear(), d.acc.resize(n), d.basin.resize(n), d.order.resize(n);
    for (std::size_t k = 0; k < n; ++k)
        if (d.down[k] >= 0) ++d.inflows[std::size_t(d.down[k])];  // at most 8
    for (std::size_t k = 0; k < n; ++k)
        if (d.inflows[k] == 0) d.topo.push_back(std::uint32_t(k));
    for (std::size_t t = 0; t < d.topo.size(); ++t) {
        const std::size_t k = d.topo[t];
        d.acc[k] = std::bit_cast<std::uint32_t>(d.cells[3 * k]) + d.p.acc[k];
        d.order[k] = std::uint8_t(std::bit_cast<std::uint32_t>(d.cells[3 * k + 2]) + d.p.order(k));
        d.p.pass(d.down[k], d.acc[k], d.order[k]);
        if (d.down[k] >= 0 && --d.inflows[std::size_t(d.down[k])] == 0) d.topo.push_back(std::uint32_t(d.down[k]));
    }
    if (d.topo.size() != n) return false;
    for (std::size_t t = n; t-- > 0;) {
        const std::size_t k = d.topo[t];
        d.basin[k] = std::bit_cast<std::uint32_t>(d.cells[3 * k + 1]) + (d.down[k] < 0 ? 0u : d.basin[std::size_t(d.down[k])]);
        if (d.basin[k] > at.basins) return false;
    }
    return true;
}

// Each basin's total of a stored network (its outlet's accumulation, as normalised_flow divides);
// false when they do not decode.
bool decode_totals(const StoredNetworkAt& at, std::vector<double>& totals) {
    std::vector<float> bits(at.basins);
    if (!decode_floats(at.totals, at.totals_size, bits.data(), bits.size(), totals_orders)) return false;
    totals.resize(bits.size());
    for (std::size_t b = 0; b < bits.size(); ++b) totals[b] = double(std::bit_cast<std::uint32_t>(bits[b]));
    return true;
}

// Whether every block and the totals of a stored network decode (a source decoded whole), on all
// cores.
bool stored_network_decodes(const CreaseSourceBytes& src, const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                            const StoredNetworkAt& at) {
    std::vector<double> totals;
    if (!decode_totals(at, totals)) return false;
    const BlockGrid grid(std::size_t(g.cols), std::size_t(g.rows), at.side);
    const GridShape shape{g.cols, g.rows, g.valid.data()};
    std::vector<std::uint8_t> ok(grid.count(), 0);
    parallel_chunks(grid.count(), 1, [&](std::size_t b0, std::size_t b1) {
        DecodedBlock d;
        for (std::size_t b = b0; b < b1; ++b) ok[b] = decode_network_block(src, grid, at, shape, dir.data(), b, d);
    });
    return std::all_of(ok.begin(), ok.end(), [](std::uint8_t v) { return v != 0; });
}

// The network a stored one gives (decode_crease_source's `net`): mains, in-degrees, and orders and
// flows filled by blocks from `src`. False when its totals do not decode.
bool stored_network(const CreaseSourceBytes& src, const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                    StoredNetworkAt&& at, FlowNetwork& net) {
    std::vector<double> totals;
    if (!decode_totals(at, totals)) return false;
    net = FlowNetwork{};
    net.mains = std::move(at.mains);
    // the in-degrees, orders and flows: not written, their pages taken (4 KiB ones) only where
    // their blocks are filled
    net.indeg.resize(g.size()), net.order.resize(g.size()), net.flow.resize(g.size());
    advise_small_pages(net.indeg.data(), net.indeg.size());
    advise_small_pages(net.order.data(), net.order.size());
    advise_small_pages(net.flow.data(), net.flow.size() * sizeof(std::uint32_t));
    const BlockGrid grid(std::size_t(g.cols), std::size_t(g.rows), at.side);
    // (the grid's mask and the directions: the caller's, which outlive the network)
    net.blocks = std::make_shared<CellBlocks>(
        grid, [src, grid, shape = GridShape{g.cols, g.rows, g.valid.data()}, dir = dir.data(), totals = std::move(totals),
               at = std::move(at), order = net.order.data(), flow = net.flow.data(), indeg = net.indeg.data()](std::size_t b) {
            DecodedBlock d;
            if (!decode_network_block(src, grid, at, shape, dir, b, d))
                throw Error("drainage", "", "stored crease source does not decode", ExitCode::internal);
            grid.each_cell(b, [&](std::size_t i, std::size_t k) {
                indeg[i] = inflow_count(shape, dir, i);
                order[i] = d.order[k];
                flow[i] = std::bit_cast<std::uint32_t>(d.basin[k] ? flow_of(d.acc[k], totals[d.basin[k] - 1]) : 0.0f);
            });
        });
    return true;
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
                          CreaseTileIndex& index, SourcePart part, std::vector<SourceUnitBlock>* blocks, FlowNetwork* net,
                          const NodeHeights* heights) {
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
    if (head.referred && !src.dem.empty()) head.dem.path = src.dem;  // moved with its database
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
            r, [&](std::uint64_t k) { return k == in_units && k <= n; }, [&](std::size_t k) { resize_in_huge_pages(cells, sources ? k : 0); },
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
            r, sized(want, may_be_empty), [&](std::size_t k) { resize_in_huge_pages(v, arrays ? k : 0); },
            [&](const std::uint8_t* c, std::size_t s, std::size_t first, std::size_t k) {
                return decode_floats(c, s, v.data() + first, k, z_orders);
            },
            arrays);
    };
    auto bytes = [&](std::vector<std::uint8_t>& v, std::size_t want, bool may_be_empty) {
        return get_blocks(
            r, sized(want, may_be_empty), [&](std::size_t k) { resize_in_huge_pages(v, arrays ? k : 0); },
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
    // (shared: left empty, the fine mask being the same at factor 1: drainage_grid.hpp)
    bool stored = false;
    StoredNetworkAt network;
    if (!get_network(r, data, cols, rows, arrays, stored, network)) return false;
    if (r.left != 0) return false;
    if (stored && arrays && !net && !stored_network_decodes(src, g, dir, network)) return false;
    // the network stored, or made from the directions and the mask
    bool made = true;
    const auto make_network = [&] {
        if (stored) made = stored_network(src, g, dir, std::move(network), *net);
        else *net = network_of_directions(g, dir);
    };
    if (!(arrays && head.referred)) {
        if (net && arrays) make_network();
        return made;
    }
    if (!net) return read_referred_arrays(head, g);
    // beside the heights read again and the positions made by blocks (which it does not read)
    bool read = false;
    run_beside(make_network, [&] { read = read_referred_arrays(head, g, true, heights); });
    return read && made;
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
                                      std::uint64_t size, std::string dem) {
    if (pages) return {static_cast<const std::uint8_t*>(pages->data(0)), std::size_t(size), pages, std::move(dem)};
    return {bytes.data(), bytes.size(), nullptr, std::move(dem)};
}

CreaseSourceBytes crease_source_bytes(const DrainageDb& db) {
    return crease_source_bytes(db.crease_source, db.crease_source_pages.get(), db.crease_source_size, db.crease_source_dem);
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
