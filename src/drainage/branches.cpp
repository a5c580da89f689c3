#include "drainage/branches.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstring>
#include <utility>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"

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
    v.flow = float(double(net.acc[i]) / total);
    return v;
}

// Rank of head cells in row-major order (= branch id): one bit per cell plus a running count
// per 64-bit word.
struct HeadRank {
    std::vector<std::uint64_t> bits;
    std::vector<std::uint32_t> before;
    std::uint32_t of(std::size_t cell) const {
        const std::uint64_t below = (std::uint64_t(1) << (cell & 63)) - 1;
        return before[cell >> 6] + std::uint32_t(std::popcount(bits[cell >> 6] & below));
    }
};

// Also counts the valid cells (`valid`). Words of bits in parallel chunks, then the running sum.
HeadRank head_rank(const DrainageGrid& g, const std::vector<std::uint8_t>& indeg, std::size_t& valid) {
    HeadRank h{std::vector<std::uint64_t>((g.size() + 63) / 64, 0), std::vector<std::uint32_t>((g.size() + 63) / 64)};
    std::atomic<std::size_t> total{0};
    parallel_chunks(h.bits.size(), 4096, [&](std::size_t w0, std::size_t w1) {
        std::size_t n = 0;
        for (std::size_t i = w0 * 64; i < std::min(g.size(), w1 * 64); ++i) {
            n += g.valid[i];
            if (g.valid[i] && indeg[i] != 1) h.bits[i >> 6] |= std::uint64_t(1) << (i & 63);
        }
        for (std::size_t w = w0; w < w1; ++w) h.before[w] = std::uint32_t(std::popcount(h.bits[w]));
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
    const std::vector<std::uint8_t> own_indeg;
    const std::vector<std::uint8_t>& indeg;
    HeadRank rank;
    std::size_t count = 0, vertices = 0;

    Heads(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net)
        : own_indeg(net.indeg.size() == g.size() ? std::vector<std::uint8_t>()
                                                 : inflow_counts(dir, GridShape{g.cols, g.rows, g.valid.data()})),
          indeg(own_indeg.empty() ? net.indeg : own_indeg) {
        std::size_t valid = 0;
        rank = head_rank(g, indeg, valid);
        count = rank.bits.empty() ? 0 : rank.before.back() + std::popcount(rank.bits.back());
        vertices = valid + count - net.outlet.size();
    }
    Heads(const Heads&) = delete;
};

struct Tracer {
    const DrainageGrid& g;
    const std::vector<std::uint8_t>& dir;
    const FlowNetwork& net;
    const std::vector<std::uint8_t>& indeg;
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

struct NetworkBranches::Walks {
    Heads heads;
    Tracer tracer;
    std::vector<std::uint32_t> head, count;  // per branch
    std::vector<std::int32_t> down;

    Walks(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net)
        : heads(g, dir, net), tracer{g, dir, net, heads.indeg, heads.rank},
          head(heads.count), count(heads.count), down(heads.count) {
        tracer.each_head(mid_cell(g), std::uint32_t(heads.count), [&](std::size_t h, std::uint32_t id, bool) {
            std::uint32_t n = 0;
            down[id] = tracer.walk(h, [&](std::size_t) { ++n; });
            head[id] = std::uint32_t(h), count[id] = n;
        });
    }
};

NetworkBranches::NetworkBranches(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net)
    : w_(std::make_unique<Walks>(g, dir, net)) {}
NetworkBranches::~NetworkBranches() = default;
std::size_t NetworkBranches::branch_count() const { return w_->head.size(); }
std::size_t NetworkBranches::vertex_count() const { return w_->heads.vertices; }

DvBranchRecord NetworkBranches::record(std::size_t id) const {
    const FlowNetwork& net = w_->tracer.net;
    const std::size_t h = w_->head[id];
    return {w_->count[id], w_->down[id], net.order[h], net.basin[h], net.acc[h]};
}

void NetworkBranches::stored_xyz(std::size_t id, std::uint8_t* out) const {
    const Tracer& t = w_->tracer;
    t.walk(w_->head[id], [&](std::size_t c) {
        const DvVertex v = point_xyz(t.g, c);
        std::memcpy(out, &v, 12);
        out += 12;
    }, false);
}

const AffineNodes* NetworkBranches::grid_nodes() const {
    const DrainageGrid& g = w_->tracer.g;
    return points_are_nodes(g) ? &g.affine : nullptr;
}

std::uint32_t NetworkBranches::head_cell(std::size_t id) const { return w_->head[id]; }

void NetworkBranches::stored_steps_z(std::size_t id, std::uint8_t* out) const {
    const Tracer& t = w_->tracer;
    const std::size_t h = w_->head[id];
    t.walk(h, [&, prev = h](std::size_t c) mutable {
        if (c != h) *out++ = std::uint8_t(d8_index(t.dir[prev]));  // the step from the vertex before
        std::memcpy(out, &t.g.z[c], 4);
        out += 4, prev = c;
    }, false);
}

namespace {

// Dual corner (i, j), i in [0, cols], j in [0, rows], sits between points (i-1..i, j-1..j).
// Edge bits: 1 north, 2 east, 4 south, 8 west; 16 marks a corner whose degree is not 2.
struct Corners {
    int cols, rows;  // corners per row / column
    std::vector<std::uint8_t> bits;
    std::size_t at(int i, int j) const { return std::size_t(j) * cols + i; }
};

constexpr int corner_di[4] = {0, 1, 0, -1}, corner_dj[4] = {-1, 0, 1, 0};

Corners divide_edges(const DrainageGrid& g, const FlowNetwork& net) {
    Corners k{g.cols + 1, g.rows + 1, std::vector<std::uint8_t>(std::size_t(g.cols + 1) * (g.rows + 1), 0)};
    auto differ = [&](std::size_t a, std::size_t b) {
        return g.valid[a] && g.valid[b] && net.basin[a] != net.basin[b];
    };
    for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = g.index(c, r);
            if (c + 1 < g.cols && differ(i, i + 1))  // corners (c+1, r) - (c+1, r+1)
                k.bits[k.at(c + 1, r)] |= 4, k.bits[k.at(c + 1, r + 1)] |= 1;
            if (r + 1 < g.rows && differ(i, i + g.cols))  // corners (c, r+1) - (c+1, r+1)
                k.bits[k.at(c, r + 1)] |= 2, k.bits[k.at(c + 1, r + 1)] |= 8;
        }
    for (std::uint8_t& b : k.bits)
        if (b && std::popcount(unsigned(b)) != 2) b |= 16;
    return k;
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
        for (int j = 0; j < k.rows; ++j)
            for (int i = 0; i < k.cols; ++i)
                while ((k.bits[k.at(i, j)] & 15) && (pass == 1 || (k.bits[k.at(i, j)] & 16)))
                    trace(g, k, i, j, std::countr_zero(unsigned(k.bits[k.at(i, j)] & 15)), db);
}

}  // namespace penink
