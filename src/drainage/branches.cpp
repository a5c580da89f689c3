#include "drainage/branches.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstring>
#include <utility>

#include "core/bit_blocks.hpp"
#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/dv_format.hpp"

namespace penink {

namespace {

// Whether the drainage points are the nodes of an affine grid (factor 1): grid_xy computes them.
bool points_are_nodes(const DrainageGrid& g) { return g.factor == 1 && g.has_affine; }

// Local x, y of drainage point i.
glm::dvec2 point_xy(const DrainageGrid& g, std::size_t i) { return grid_xy(g, int(i % g.cols), int(i / g.cols)); }

// x, y, z of drainage point i (flow 0).
DvVertex point_xyz(const DrainageGrid& g, std::size_t i) {
    const glm::dvec2 p = point_xy(g, i);
    return {float(p.x), float(p.y), g.z[i], 0.0f};
}

// `total` is the accumulation at the outlet of the point's basin (as normalised_flow divides).
DvVertex point_vertex(const DrainageGrid& g, const FlowNetwork& net, std::size_t i, double total) {
    DvVertex v = point_xyz(g, i);
    v.flow = flow_of(net.acc[i], total);
    return v;
}

// Bits set in x, without the libgcc call std::popcount makes on baseline x86-64 (no POPCNT).
inline std::uint32_t bit_count(std::uint64_t x) {
    x -= (x >> 1) & 0x5555555555555555ull;
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return std::uint32_t((x * 0x0101010101010101ull) >> 56);
}

// Rank of head cells in row-major order (= branch id): one bit per cell plus a running count
// per 64-bit word.
struct HeadRank {
    std::vector<std::uint64_t> bits;
    std::vector<std::uint32_t> before;
    std::uint32_t of(std::size_t cell) const {
        const std::uint64_t below = (std::uint64_t(1) << (cell & 63)) - 1;
        return before[cell >> 6] + bit_count(bits[cell >> 6] & below);
    }
    // The head of rank k (< the number of heads): the word holding it by binary search, then its
    // (k - before)-th set bit.
    std::size_t select(std::uint32_t k) const {
        const std::size_t w = std::size_t(std::upper_bound(before.begin(), before.end(), k) - before.begin()) - 1;
        std::uint64_t b = bits[w];
        for (std::uint32_t skip = k - before[w]; skip > 0; --skip) b &= b - 1;
        return w * 64 + std::size_t(std::countr_zero(b));
    }
};

// Also counts the valid cells (`valid`). Words of bits in parallel chunks, then the running sum.
HeadRank head_rank(const DrainageGrid& g, const CellBytes& indeg, std::size_t& valid) {
    HeadRank h{std::vector<std::uint64_t>((g.size() + 63) / 64, 0), std::vector<std::uint32_t>((g.size() + 63) / 64)};
    std::atomic<std::size_t> total{0};
    parallel_chunks(h.bits.size(), 4096, [&](std::size_t w0, std::size_t w1) {
        std::size_t n = 0;
        for (std::size_t w = w0; w < w1; ++w) {  // a word of 64 cells at a time, without branches
            const std::size_t i0 = w * 64, i1 = std::min(g.size(), i0 + 64);
            std::uint64_t bits = 0;
            for (std::size_t i = i0; i < i1; ++i) {
                n += g.valid[i];
                bits |= std::uint64_t((g.valid[i] != 0) & (indeg[i] != 1)) << (i - i0);
            }
            h.bits[w] = bits, h.before[w] = bit_count(bits);
        }
        total += n;
    });
    std::uint32_t n = 0;
    for (std::uint32_t& b : h.before) n += std::exchange(b, n);  // counts -> running sums before
    valid = total;
    return h;
}

// The branch heads of a network (valid cells whose in-degree is not 1), ranked in row-major order
// (= branch ids), with the in-degrees they come from (the network's, or counted when it has
// none), how many there are and how many vertices the branches hold: every valid point once plus
// the repeated end junction of each branch that does not end at an outlet (one per basin does).
// Not movable: `indeg` may refer to own_indeg.
struct Heads {
    const CellBytes own_indeg;
    const CellBytes& indeg;
    HeadRank rank;
    std::size_t count = 0, vertices = 0;

    Heads(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net)
        : own_indeg(net.indeg.size() == g.size() ? CellBytes()
                                                 : inflow_counts(dir, GridShape{g.cols, g.rows, g.valid.data()})),
          indeg(own_indeg.empty() ? net.indeg : own_indeg) {
        std::size_t valid = 0;
        rank = head_rank(g, indeg, valid);
        count = rank.bits.empty() ? 0 : rank.before.back() + bit_count(rank.bits.back());
        vertices = valid + count - net.outlet.size();
    }
    Heads(const Heads&) = delete;
};

struct Tracer {
    const DrainageGrid& g;
    const std::vector<std::uint8_t>& dir;
    const FlowNetwork& net;
    const CellBytes& indeg;
    const HeadRank& rank;
    GridShape shape{g.cols, g.rows, g.valid.data()};

    bool is_head(std::size_t h) const { return g.valid[h] && indeg[h] != 1; }
    [[noreturn]] static void overflow() {
        throw Error("drainage", "", "branches overflow the database (a point or a head counted twice)",
                    ExitCode::internal);
    }

    // Walks the branch headed at cell h: emit(cell) for each of its points and, when it ends at
    // a junction and end_too is set, for that junction too (the downstream branch's head,
    // repeated as its last vertex; a DV file does not store it); returns the downstream branch's
    // id, -1 at an outlet.
    template <class Emit> std::int32_t walk(std::size_t h, Emit&& emit, bool end_too = true) const {
        for (std::size_t c = h;;) {
            emit(c);
            if (!dir[c]) return -1;
            const std::size_t d = d8_target(shape, c, dir[c]);
            if (indeg[d] != 1) {
                if (end_too) emit(d);
                return std::int32_t(rank.of(d));
            }
            c = d;
        }
    }

    // Calls f(head, id, south) for every head with its branch id (heads in cell order): those
    // before cell `mid` on this thread from id 0 up, the rest on a second thread (south = true)
    // from the last id down. The two must meet.
    template <class F> void each_head(std::size_t mid, std::uint32_t heads, F&& f) const {
        std::uint32_t north_id = 0, south_id = heads;
        run_beside(
            [&] {
                for (std::size_t h = g.size(); h-- > mid;)
                    if (is_head(h)) south_id == 0 ? overflow() : f(h, --south_id, true);
            },
            [&] {
                for (std::size_t h = 0; h < mid; ++h)
                    if (is_head(h)) north_id >= heads ? overflow() : f(h, north_id++, false);
            });
        if (north_id != south_id) overflow();
    }
};

std::size_t mid_cell(const DrainageGrid& g) { return std::size_t(g.rows / 2) * g.cols; }

// North heads forward from the start of db.vertices, south heads backward from its end (each
// half on its own thread, each_head); the two must meet exactly.
void trace_halves(const Tracer& tracer, DrainageDb& db) {
    std::vector<double> total(tracer.net.outlet.size());  // accumulation at each basin's outlet
    for (std::size_t b = 0; b < total.size(); ++b) total[b] = tracer.net.acc[tracer.net.outlet[b]];
    std::vector<DvVertex> run[2];
    std::size_t at[2] = {0, db.vertices.size()};  // north: next free; south: first written
    tracer.each_head(mid_cell(tracer.g), std::uint32_t(db.branches.size()), [&](std::size_t h, std::uint32_t id, bool south) {
        const FlowNetwork& net = tracer.net;
        DvBranch b{};
        b.basin = net.basin[h], b.order = net.order[h], b.head_acc = net.acc[h];
        const double t = total[b.basin - 1];  // a flow path stays in its basin
        std::vector<DvVertex>& r = run[south];
        r.clear();
        b.downstream = tracer.walk(h, [&](std::size_t c) { r.push_back(point_vertex(tracer.g, net, c, t)); });
        b.count = std::uint32_t(r.size());
        // each half bounds itself by the array's ends (the other half's cursor is its thread's)
        if (south ? r.size() > at[1] : r.size() > db.vertices.size() - at[0]) Tracer::overflow();
        b.first = std::uint32_t(south ? (at[1] -= r.size()) : at[0]);
        std::copy(r.begin(), r.end(), db.vertices.begin() + std::ptrdiff_t(b.first));
        if (!south) at[0] += r.size();
        db.branches[id] = b;
    });
    if (at[0] != at[1])
        throw Error("drainage", "", "branch vertices do not fill the database (a point off every branch)",
                    ExitCode::internal);
}

}  // namespace

// Sizes are known before tracing: every valid point is stored once, plus the repeated end
// junction of each branch that does not end at an outlet (one branch per basin does). Two
// threads trace the heads of the north half forward from the start and those of the south half
// backward from the end of the one vertex array: the same result as one pass in cell order,
// without a second copy of the vertices.
void build_branches(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                    const FlowNetwork& net, DrainageDb& db) {
    const Heads heads(g, dir, net);
    db.vertices.clear();
    db.vertices.resize(heads.vertices);  // untouched: the threads fault their halves
    db.branches.clear();
    db.branches.resize(heads.count);  // untouched: every record is written by the thread tracing it
    trace_halves(Tracer{g, dir, net, heads.indeg, heads.rank}, db);
    link_upstream(db.branches, db.upstream);
}

struct NetworkBranches::Walks {  // the heads and a tracer over them; each encode() walks its branches
    Heads heads;
    Tracer tracer;
    std::size_t links;

    Walks(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net)
        : heads(g, dir, net), tracer{g, dir, net, heads.indeg, heads.rank},
          links(heads.count - net.outlet.size()) {}
};

NetworkBranches::NetworkBranches(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net)
    : w_(std::make_unique<Walks>(g, dir, net)) {}
NetworkBranches::~NetworkBranches() = default;
std::size_t NetworkBranches::branch_count() const { return w_->heads.count; }
std::size_t NetworkBranches::vertex_count() const { return w_->heads.vertices; }
std::size_t NetworkBranches::link_count() const { return w_->links; }

const AffineNodes* NetworkBranches::grid_nodes() const {
    const DrainageGrid& g = w_->tracer.g;
    return points_are_nodes(g) ? &g.affine : nullptr;
}

namespace {

// The heads from rank k on, in rank (= cell) order: the rank's bit words scanned a word at a time.
struct HeadCursor {
    const HeadRank& rank;
    std::size_t word = 0;
    std::uint64_t bits = 0;
    HeadCursor(const HeadRank& r, std::uint32_t k) : rank(r) {
        const std::size_t h = r.select(k);
        word = h >> 6, bits = r.bits[word] & (~std::uint64_t(0) << (h & 63));
    }
    std::size_t next() {
        while (!bits) bits = rank.bits[++word];
        const std::size_t h = word * 64 + std::size_t(std::countr_zero(bits));
        bits &= bits - 1;
        return h;
    }
};

// Appends the stored vertices of a branch walked into `cells` (its end junction included) at p:
// x, y, z, or on grid nodes the step from the vertex before and z (dv_format.hpp).
std::uint8_t* put_cells(std::uint8_t* p, const Tracer& t, bool grid, const std::vector<std::uint32_t>& cells,
                        std::uint32_t stored) {
    for (std::uint32_t k = 0; k < stored; ++k) {
        if (!grid) {
            const DvVertex v = point_xyz(t.g, cells[k]);
            std::memcpy(p, &v, 12), p += 12;
            continue;
        }
        if (k > 0) *p++ = std::uint8_t(d8_index(t.dir[cells[k - 1]]));
        std::memcpy(p, &t.g.z[cells[k]], 4), p += 4;
    }
    return p;
}

}  // namespace

// Each branch walked once into `cells`, then its record and its stored vertices appended.
void NetworkBranches::encode(std::size_t b0, std::size_t b1, DvBytes& out) const {
    if (b0 >= b1) return;
    const Tracer& t = w_->tracer;
    const bool grid = grid_nodes() != nullptr;
    std::vector<std::uint32_t> cells;
    HeadCursor heads(t.rank, std::uint32_t(b0));
    std::uint32_t before = b0 ? std::uint32_t(t.rank.select(std::uint32_t(b0 - 1))) : 0;  // head deltas
    for (std::size_t id = b0; id < b1; ++id) {
        const std::size_t h = heads.next();
        cells.clear();
        const std::int32_t down = t.walk(h, [&](std::size_t c) { cells.push_back(std::uint32_t(c)); });
        const DvBranchRecord r{std::uint32_t(cells.size()), down, t.net.order[h], t.net.basin[h], t.net.acc[h]};
        dv::append_branch(out, r, id, grid, std::uint32_t(h) - before,
                          [&](std::uint8_t* p) { return put_cells(p, t, grid, cells, dv::stored_count(r)); });
        before = std::uint32_t(h);
    }
}

namespace {

// Dual corner (i, j), i in [0, cols], j in [0, rows], sits between points (i-1..i, j-1..j).
// Edge bits: 1 north, 2 east, 4 south, 8 west; 16 marks a corner whose degree is not 2.
struct Corners {
    int cols, rows;  // corners per row / column
    DvBytes bits;    // every corner's written by divide_edges
    std::size_t at(int i, int j) const { return std::size_t(j) * cols + i; }
};

constexpr int corner_di[4] = {0, 1, 0, -1}, corner_dj[4] = {-1, 0, 1, 0};

// Bits of a corner from the basins (0: invalid or off the grid) of its up-left, up-right,
// down-left and down-right points: no branch, so a row of corners vectorises.
inline std::uint8_t corner_bits(std::uint32_t ul, std::uint32_t ur, std::uint32_t dl, std::uint32_t dr) {
    auto differ = [](std::uint32_t a, std::uint32_t b) { return unsigned((a != 0) & (b != 0) & (a != b)); };
    const unsigned b = differ(ul, ur) | differ(ur, dr) << 1 | differ(dl, dr) << 2 | differ(ul, dl) << 3;
    const unsigned degree = (b & 1) + (b >> 1 & 1) + (b >> 2 & 1) + (b >> 3 & 1);
    return std::uint8_t(b | ((b != 0) & (degree != 2)) << 4);
}

// Each corner's bits from its (up to) four surrounding points' basins (0 where invalid or off the
// grid): an edge leaves corner (i, j) north between points (i-1, j-1) and (i, j-1), east between
// (i, j-1) and (i, j), south between (i-1, j) and (i, j), west between (i-1, j-1) and (i-1, j),
// when both are valid and their basins differ. On the calling thread: it runs beside the
// accumulation, which has the other core.
Corners divide_edges(const DrainageGrid& g, const FlowNetwork& net) {
    Corners k{g.cols + 1, g.rows + 1, DvBytes(std::size_t(g.cols + 1) * (g.rows + 1))};
    const std::vector<std::uint32_t> none(std::size_t(g.cols), 0);  // the rows beyond the grid
    for (int j = 0; j < k.rows; ++j) {
        const std::uint32_t* up = j > 0 ? net.basin.data() + g.index(0, j - 1) : none.data();
        const std::uint32_t* down = j < g.rows ? net.basin.data() + g.index(0, j) : none.data();
        std::uint8_t* out = k.bits.data() + k.at(0, j);
        out[0] = corner_bits(0, up[0], 0, down[0]);
        // most corners lie inside one basin (bits 0): the four basins are alike unless one of
        // three steps around the corner differs
        std::memset(out + 1, 0, std::size_t(g.cols - 1));
        each_where(
            1, g.cols, [&](int i) { return (up[i - 1] != up[i]) | (up[i] != down[i]) | (down[i] != down[i - 1]); },
            [&](int i) { out[i] = corner_bits(up[i - 1], up[i], down[i - 1], down[i]); });
        out[g.cols] = corner_bits(up[g.cols - 1], 0, down[g.cols - 1], 0);
    }
    return k;
}

// The next corner at or after `at` with an edge (k.bits.size() when none): eight corners at a time
// through the many without one.
std::size_t next_with_edge(const Corners& k, std::size_t at) {
    constexpr std::uint64_t edge_bits = 0x0f0f0f0f0f0f0f0full;
    const std::size_t n = k.bits.size();
    for (std::uint64_t w; at + 8 <= n; at += 8) {
        std::memcpy(&w, k.bits.data() + at, 8);
        if (w & edge_bits) break;
    }
    while (at < n && !(k.bits[at] & 15)) ++at;
    return at;
}

DvVertex corner_vertex(const DrainageGrid& g, int i, int j) {
    glm::dvec2 sum(0.0);
    float zmax = -1e30f;
    int n = 0;
    for (int r = j - 1; r <= j; ++r)
        for (int c = i - 1; c <= i; ++c) {
            if (c < 0 || r < 0 || c >= g.cols || r >= g.rows || !g.valid[g.index(c, r)]) continue;
            sum += grid_xy(g, c, r), zmax = std::max(zmax, g.z[g.index(c, r)]), ++n;
        }
    DvVertex v{};
    v.x = float(sum.x / n), v.y = float(sum.y / n), v.z = zmax;
    return v;
}

// Follows edges from corner (i, j) leaving by `e` until a corner of degree != 2 or the start.
void trace(const DrainageGrid& g, Corners& k, int i, int j, int e, DrainageDb& db) {
    DvPolyline line{std::uint32_t(db.divide_vertices.size()), 0};
    const int i0 = i, j0 = j;
    db.divide_vertices.push_back(corner_vertex(g, i, j));
    for (;;) {
        k.bits[k.at(i, j)] &= std::uint8_t(~(1u << e));
        i += corner_di[e], j += corner_dj[e];
        std::uint8_t& b = k.bits[k.at(i, j)];
        b &= std::uint8_t(~(1u << ((e + 2) & 3)));
        db.divide_vertices.push_back(corner_vertex(g, i, j));
        if ((b & 16) || (b & 15) == 0 || (i == i0 && j == j0)) break;
        e = std::countr_zero(unsigned(b & 15));
    }
    line.count = std::uint32_t(db.divide_vertices.size()) - line.first;
    db.divides.push_back(line);
}

}  // namespace

void build_divides(const DrainageGrid& g, const FlowNetwork& net, DrainageDb& db) {
    Corners k = divide_edges(g, net);
    db.divide_vertices.clear(), db.divides.clear();
    for (int pass = 0; pass < 2; ++pass)  // open chains from nodes first, then closed loops
        for (std::size_t at = next_with_edge(k, 0); at < k.bits.size(); at = next_with_edge(k, at + 1)) {
            const int i = int(at % std::size_t(k.cols)), j = int(at / std::size_t(k.cols));
            while ((k.bits[at] & 15) && (pass == 1 || (k.bits[at] & 16)))
                trace(g, k, i, j, std::countr_zero(unsigned(k.bits[at] & 15)), db);
        }
}

}  // namespace penink
