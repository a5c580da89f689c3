#include "drainage/draped_lines.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <type_traits>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "core/u32_map.hpp"
#include "drainage/d8.hpp"
#include "drainage/stems.hpp"
#include "drainage/fall_line_stems.hpp"
#include "drainage/line_chunks.hpp"
#include "drainage/polyline_smoothing.hpp"
#include "drainage/ridge_crests.hpp"

namespace penink {

namespace {

// The drainage stems walked on the network's cells (drainage_stems on the branches the network
// gives, build_branches): a stem starts at each source (a valid cell nothing drains into; cell
// order = branch order), runs down its branch and on through every junction whose main upstream
// branch it arrives by, and ends at an outlet or with the junction where it joins another stem.
struct StemWalk {
    const DrainageGrid& g;
    const std::vector<std::uint8_t>& dir;
    const FlowNetwork& net;
    GridShape shape{g.cols, g.rows, g.valid.data()};
    CellBytes own_indeg;
    const CellBytes& indeg;
    std::vector<double> total;  // accumulation at each basin's outlet
    const float* z = node_heights(g);

    StemWalk(const DrainageGrid& grid, const std::vector<std::uint8_t>& d, const FlowNetwork& n)
        : g(grid), dir(d), net(n),
          own_indeg(n.indeg.size() == grid.size() ? CellBytes() : inflow_counts(d, shape)),
          indeg(own_indeg.empty() ? n.indeg : own_indeg) {
        if (net.flow.empty()) {  // (keep_normalised_flow: each cell's flow, no accumulation)
            total.resize(net.outlet.size());
            for (std::size_t b = 0; b < total.size(); ++b) total[b] = net.acc[net.outlet[b]];
        }
    }
    StemWalk(const StemWalk&) = delete;

    // The drainage vertex of cell i (build_branches' point_vertex; grid_xy's nodes read here
    // where it would read them from coarse_xy).
    const bool node_xy = g.factor == 1 && !g.has_affine && g.coarse_xy.size() == g.size();
    glm::vec2 xy(std::size_t i) const {
        if (node_xy) need_node(g, i);
        const glm::dvec2 p = node_xy ? glm::dvec2(g.coarse_xy[i])
                                     : grid_xy(g, int(i % std::size_t(g.cols)), int(i / std::size_t(g.cols)));
        return {float(p.x), float(p.y)};
    }
    DvVertex vertex(std::size_t i) const {
        const glm::vec2 p = xy(i);
        need_node(g, i);  // (its height: by blocks too, also on an affine grid)
        return {p.x, p.y, z[i], vertex_flow(i)};
    }

    // Calls f(m) for each valid cell draining into cell d.
    template <class F> void each_upstream(std::size_t d, F&& f) const {
        const int c = int(d % std::size_t(g.cols)), r = int(d / std::size_t(g.cols));
        for (int k = 0; k < 8; ++k) {
            const int mc = c - d8_dc[k], mr = r - d8_dr[k];
            if (mc < 0 || mr < 0 || mc >= g.cols || mr >= g.rows) continue;
            const std::size_t m = g.index(mc, mr);
            if (g.valid[m] && dir[m] == std::uint8_t(1u << k)) f(m);
        }
    }

    // Head of the branch holding cell m (= its branch id's rank): up through single-inflow cells.
    std::size_t head(std::size_t m) const {
        for (std::size_t steps = 0; need(m), indeg[m] == 1; ++steps) {
            if (steps > g.size()) cycle();
            std::size_t up = m;
            each_upstream(m, [&](std::size_t u) { up = u; });
            m = up;
        }
        return m;
    }

    // The upstream cell of junction d whose branch is d's main upstream branch (stems.cpp
    // main_upstream: highest order, then larger flow just above the junction, then the lower
    // branch id: of those tied, the one whose branch has the least head); d when none drains into it.
    std::size_t main_upstream(std::size_t d) const {
        struct Candidate {
            std::size_t cell;
            std::uint8_t order;
            float flow;
        };
        Candidate c[8];
        int k = 0, best = -1;
        each_upstream(d, [&](std::size_t m) {
            need(m);
            c[k] = {m, net.order[m], vertex_flow(m)};
            if (best < 0 || c[k].order > c[best].order || (c[k].order == c[best].order && c[k].flow > c[best].flow))
                best = k;
            ++k;
        });
        if (best < 0) return d;
        std::size_t main = c[best].cell;
        bool tied = false;
        for (int i = 0; i < k; ++i)
            if (i != best && c[i].order == c[best].order && c[i].flow == c[best].flow) tied = true;
        if (!tied) return main;
        std::size_t main_head = head(main);  // (distinct cells' branches have distinct heads)
        for (int i = 0; i < k; ++i)
            if (i != best && c[i].order == c[best].order && c[i].flow == c[best].flow)
                if (const std::size_t h = head(c[i].cell); h < main_head) main = c[i].cell, main_head = h;
        return main;
    }

    // Whether the branch arriving at junction d through cell n (draining into it) is d's main
    // upstream branch: its bit in `mains` where the junctions' mains were found, else found here.
    bool main_into(std::size_t n, std::size_t d) const { return mains ? is_main(n) : main_upstream(d) == n; }
    bool is_main(std::size_t n) const { return (mains[n >> 6] >> (n & 63)) & 1u; }

    // main_upstream(d) of a junction d (two or more cells drain into it): the one cell draining
    // into it whose bit is set, where the mains were found.
    std::size_t junction_main(std::size_t d) const {
        if (!mains) return main_upstream(d);
        std::size_t main = d;
        each_upstream(d, [&](std::size_t u) {
            if (is_main(u)) main = u;
        });
        return main;
    }

    // The mains found (main_upstream_bits): net.mains where the network has them, else found
    // here when `find` (a walk over every stem asks each junction once for every stem arriving
    // there, by random reads of its neighbours' arrays).
    std::vector<std::uint64_t> own_mains;
    const std::uint64_t* mains = nullptr;
    void use_mains(bool find) {
        if (net.mains.size() == mains_words(g.size())) mains = net.mains.data();
        else if (find) own_mains = main_upstream_bits(g, dir, net), mains = own_mains.data();
    }

    // The cell one step up the stem walking through cell m: the one cell draining into a
    // single-inflow cell, the main upstream one at a junction; m itself at a cell nothing valid
    // drains into (a source).
    std::size_t main_up(std::size_t m) const {
        std::size_t up = m;
        need(m);
        if (indeg[m] == 1) each_upstream(m, [&](std::size_t u) { up = u; });
        else if (indeg[m] > 1) up = junction_main(m);
        return up;
    }

    // Cell i's in-degree, order and flow made to hold their values (a network filled by blocks:
    // CellBlocks).
    void need(std::size_t i) const {
        if (net.blocks) net.blocks->need(i);
    }

    float vertex_flow(std::size_t i) const {
        return net.flow.empty() ? flow_of(net.acc[i], total[net.basin[i] - 1]) : std::bit_cast<float>(net.flow[i]);
    }

    [[noreturn]] static void cycle() {
        throw Error("drainage", "", "flow directions contain a cycle (stem without an end)", ExitCode::internal);
    }

    // Emits the cells of the stem starting at `source` (emit(vertex, cell)), dropping a vertex at
    // the x, y of the one before it (drainage_stems' shared junction rule); returns the stem's order.
    // An emit returning bool ends the walk where it returns false (the order then of the cells
    // walked so far).
    template <class Emit> std::uint8_t walk(std::size_t source, Emit&& emit) const {
        std::uint8_t order = 0;
        DvVertex last{};
        bool any = false, more = true;
        auto put = [&](std::size_t c) {
            need(c);
            const DvVertex v = vertex(c);
            if (any && last.x == v.x && last.y == v.y) return;
            if constexpr (std::is_same_v<decltype(emit(v, c)), bool>) more = emit(v, c);
            else emit(v, c);
            last = v, any = true;
        };
        std::size_t c = source;
        for (std::size_t steps = 0; steps <= g.size(); ++steps) {
            put(c);
            order = std::max(order, net.order[c]);
            if (!more || !dir[c]) return order;
            const std::size_t d = d8_target(shape, c, dir[c]);
            need(d);
            if (indeg[d] != 1 && !main_into(c, d)) {
                put(d);
                return order;
            }
            c = d;
        }
        cycle();
    }
};

DrapedVertex draped(const DvVertex& v) { return {v.x, v.y, v.z, 0.0f, 0.0f, 0.0f, v.flow}; }

std::uint64_t xy_key(const DrapedVertex& v) {
    return (std::uint64_t(std::bit_cast<std::uint32_t>(v.x)) << 32) | std::bit_cast<std::uint32_t>(v.y);
}

// The x, y keys of the lines' ends (open addressing, 12 bytes a slot, 1.5 slots an end), each
// with the first interior vertex (in line order) at the same x, y: the end matches (draped_lines.hpp,
// step 2), found before smoothing. Made on all cores: the ends inserted with compare-and-swap (where a key
// lands may depend on the threads, what a lookup finds does not), the interior vertices looked
// up through a bitmap of the ends' hashes (1 bit in 8 set at most; 1 bit an end) that turns most
// of them away before the table's random reads, and the least matching vertex kept.
class EndMatches {
public:
    explicit EndMatches(const DrapedLineSet& set) {
        std::size_t ends = 0;
        for (const DrapedLine& l : set.lines) ends += l.count >= 2 ? 2 : 0;
        key_.resize(std::max<std::size_t>(16, ends + ends / 2));
        first_.resize(key_.size());
        filter_bits_ = 64;
        while (filter_bits_ < 8 * ends) filter_bits_ *= 2;
        filter_.resize(filter_bits_ / 64);
        parallel_chunks(key_.size(), 1 << 16, [&](std::size_t s0, std::size_t s1) {
            std::fill(key_.begin() + std::ptrdiff_t(s0), key_.begin() + std::ptrdiff_t(s1), empty);
            std::fill(first_.begin() + std::ptrdiff_t(s0), first_.begin() + std::ptrdiff_t(s1), none);
        });
        parallel_chunks(filter_.size(), 1 << 14, [&](std::size_t w0, std::size_t w1) {
            std::fill(filter_.begin() + std::ptrdiff_t(w0), filter_.begin() + std::ptrdiff_t(w1), std::uint64_t(0));
        });
        parallel_chunks(set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1) {
            for (std::size_t i = l0; i < l1; ++i) {
                const DrapedLine& l = set.lines[i];
                if (l.count >= 2)
                    for (std::uint32_t e : {l.first, l.first + l.count - 1}) insert(xy_key(set.vertices[e]));
            }
        });
        // interior vertices (lines of 3 or more), on all cores; the least index wins
        parallel_chunks(set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1) {
            for (std::size_t i = l0; i < l1; ++i) {
                const DrapedLine& l = set.lines[i];
                for (std::uint32_t k = 1; k + 1 < l.count; ++k) {
                    const std::uint64_t key = xy_key(set.vertices[l.first + k]);
                    if (!maybe(key)) continue;
                    const std::size_t s = find(key);
                    if (s == npos) continue;
                    std::atomic_ref<std::uint32_t> best(first_[s]);
                    std::uint32_t seen = best.load(std::memory_order_relaxed);
                    while (l.first + k < seen && !best.compare_exchange_weak(seen, l.first + k)) {
                    }
                }
            }
        });
    }
    // The interior vertex an end at x, y follows, or `none`.
    std::uint32_t target(const DrapedVertex& v) const {
        const std::size_t s = find(xy_key(v));
        return s == npos ? none : first_[s];
    }
    static constexpr std::uint32_t none = 0xffffffffu;

private:
    static constexpr std::size_t npos = std::size_t(-1);
    static constexpr std::uint64_t empty = ~std::uint64_t(0);  // NaN, NaN: no vertex's x, y
    std::vector<std::uint64_t, UninitAllocator<std::uint64_t>> key_;
    std::vector<std::uint32_t, UninitAllocator<std::uint32_t>> first_;
    std::vector<std::uint64_t, UninitAllocator<std::uint64_t>> filter_;
    std::size_t filter_bits_ = 64;  // a power of 2

    static std::uint64_t mix(std::uint64_t k) {
        k ^= k >> 31, k *= 0x7fb5d329728ea185ull, k ^= k >> 27, k *= 0x81dadef4bc2dd44dull, k ^= k >> 33;
        return k;
    }
    std::size_t slot(std::uint64_t k) const { return std::size_t((unsigned __int128)mix(k) * key_.size() >> 64); }
    std::size_t bit(std::uint64_t k) const { return std::size_t(mix(k)) & (filter_bits_ - 1); }
    bool maybe(std::uint64_t k) const {
        const std::size_t b = bit(k);
        return (filter_[b >> 6] >> (b & 63)) & 1u;
    }
    void insert(std::uint64_t k) {
        if (k == empty) return;
        const std::size_t b = bit(k);
        std::atomic_ref<std::uint64_t>(filter_[b >> 6]).fetch_or(std::uint64_t(1) << (b & 63), std::memory_order_relaxed);
        for (std::size_t s = slot(k);; s = s + 1 == key_.size() ? 0 : s + 1) {
            std::atomic_ref<std::uint64_t> at(key_[s]);
            std::uint64_t seen = at.load(std::memory_order_relaxed);
            if (seen == k) return;
            if (seen == empty) {
                if (at.compare_exchange_strong(seen, k, std::memory_order_relaxed) || seen == k) return;
            }
        }
    }
    std::size_t find(std::uint64_t k) const {
        if (k == empty) return npos;
        for (std::size_t s = slot(k);; s = s + 1 == key_.size() ? 0 : s + 1) {
            if (key_[s] == empty) return npos;
            if (key_[s] == k) return s;
        }
    }
};

// Gaussian smoothing (gaussian_smooth) of each line's x, y, on all cores.
void smooth_each_line(DrapedLineSet& set, double sigma) {
    parallel_chunks(set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1) {
        std::vector<glm::dvec2> p, q;
        for (std::size_t i = l0; i < l1; ++i) {
            const DrapedLine& l = set.lines[i];
            if (l.count < 3) continue;
            DrapedVertex* v = set.vertices.data() + l.first;
            p.resize(l.count);
            for (std::uint32_t k = 0; k < l.count; ++k) p[k] = {v[k].x, v[k].y};
            gaussian_smooth(p, sigma, q);
            for (std::uint32_t k = 0; k < l.count; ++k) v[k].x = float(q[k].x), v[k].y = float(q[k].y);
        }
    });
}

// The plan box of a set's vertices (per chunk on all cores, the chunks' boxes joined in order:
// glm::min and max keep the first of equal values, as one pass does).
void vertex_box(const DrapedLineSet& set, glm::vec2& lo, glm::vec2& hi) {
    struct Box {
        glm::vec2 lo, hi;
    };
    const std::vector<Box> boxes = parallel_collect<Box>(set.vertices.size(), 1 << 16, [&](std::size_t i0, std::size_t i1, std::vector<Box>& out) {
        Box b{glm::vec2(std::numeric_limits<float>::infinity()), glm::vec2(-std::numeric_limits<float>::infinity())};
        for (std::size_t i = i0; i < i1; ++i) {
            const DrapedVertex& v = set.vertices[i];
            b.lo = glm::min(b.lo, glm::vec2(v.x, v.y)), b.hi = glm::max(b.hi, glm::vec2(v.x, v.y));
        }
        out.push_back(b);
    });
    lo = glm::vec2(std::numeric_limits<float>::infinity()), hi = -lo;
    for (const Box& b : boxes) lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi);
}

// Every vertex's x, y clamped to [lo, hi]: smoothed lines stay inside the box the network's own
// vertices span (inside the DEM's, which a frame cuts lines to).
void clamp_to_box(DrapedLineSet& set, glm::vec2 lo, glm::vec2 hi) {
    if (!(lo.x <= hi.x && lo.y <= hi.y)) return;
    parallel_chunks(set.vertices.size(), 1 << 16, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i) {
            DrapedVertex& v = set.vertices[i];
            v.x = std::clamp(v.x, lo.x, hi.x), v.y = std::clamp(v.y, lo.y, hi.y);
        }
    });
}

// The line holding each vertex.
std::vector<std::uint32_t, UninitAllocator<std::uint32_t>> line_ids(const DrapedLineSet& set) {
    std::vector<std::uint32_t, UninitAllocator<std::uint32_t>> out(set.vertices.size());
    parallel_chunks(set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1) {
        for (std::size_t i = l0; i < l1; ++i)
            std::fill_n(out.begin() + set.lines[i].first, set.lines[i].count, std::uint32_t(i));
    });
    return out;
}

// The end matches of the set as it is: (line, end vertex, interior vertex) triples, in line order
// (a line's first end before its last).
std::vector<std::uint32_t> end_matches(const DrapedLineSet& set) {
    const EndMatches matches(set);
    return parallel_collect<std::uint32_t>(set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1, std::vector<std::uint32_t>& follow) {
        for (std::size_t i = l0; i < l1; ++i) {
            const DrapedLine& l = set.lines[i];
            if (l.count >= 2)
                for (std::uint32_t e : {l.first, l.first + l.count - 1})
                    if (const std::uint32_t t = matches.target(set.vertices[e]); t != EndMatches::none)
                        follow.push_back(std::uint32_t(i)), follow.push_back(e), follow.push_back(t);
        }
    });
}

// Each matched end brought to its line's new x, y: three rounds in which every end's gap to its
// target is closed over the vertices next to it, as many as make the gap at most tan 8 degrees of
// their length (at least `ramp`; weights (1 + cos(pi j / m)) / 2 over m vertices, j = 0 at the
// end: the line bends smoothly to its junction; all gaps of a round measured before any is
// closed, so the result does not depend on the order), then the end set to it exactly.
// On all cores: the gaps of a round in any order, the closing by whole lines (the two ends of a
// line in turn, as their ramps may meet), each moving only its own line's vertices.
inline double plan_length(double x, double y) { return std::sqrt(x * x + y * y); }

// The ramp's weight of vertex j of m (the formula of join_ends); those of m up to `memo` made
// once a thread.
class RampWeights {
public:
    float operator()(std::uint32_t j, std::uint32_t m) {
        if (m > memo) return weight(j, m);
        if (m >= first_.size()) first_.resize(m + 1, none);
        if (first_[m] == none) {
            first_[m] = std::uint32_t(w_.size());
            for (std::uint32_t k = 0; k < m; ++k) w_.push_back(weight(k, m));
        }
        return w_[first_[m] + j];
    }

private:
    static constexpr std::uint32_t memo = 256, none = 0xffffffffu;
    std::vector<std::uint32_t> first_;
    std::vector<float> w_;
    static float weight(std::uint32_t j, std::uint32_t m) {
        return 0.5f * (1.0f + std::cos(3.14159265358979f * float(j) / float(m)));
    }
};

void join_ends(DrapedLineSet& set, const std::vector<std::uint32_t>& follow, int ramp) {
    constexpr double tan_bend = 0.14054083470239145;  // tan 8 degrees
    const std::size_t nf = follow.size() / 3;
    std::vector<glm::vec2> gap(nf);
    // the follows of each line together (end_matches gives them in line order): closed by one task
    std::vector<std::uint32_t> group;
    for (std::size_t k = 0; k < nf; ++k)
        if (k == 0 || follow[3 * k] != follow[3 * k - 3]) group.push_back(std::uint32_t(k));
    group.push_back(std::uint32_t(nf));
    const std::size_t ng = group.size() - 1;
    for (int round = 0; round < 3 && ramp > 1; ++round) {
        parallel_chunks(nf, 4096, [&](std::size_t k0, std::size_t k1) {
            for (std::size_t k = k0; k < k1; ++k) {
                const DrapedVertex &e = set.vertices[follow[3 * k + 1]], &t = set.vertices[follow[3 * k + 2]];
                gap[k] = {t.x - e.x, t.y - e.y};
            }
        });
        parallel_chunks(ng, 1024, [&](std::size_t g0, std::size_t g1) {
            RampWeights weights;
            for (std::size_t k = group[g0]; k < group[g1]; ++k) {
                const DrapedLine& l = set.lines[follow[3 * k]];
                const bool first = follow[3 * k + 1] == l.first;
                auto at = [&](std::uint32_t j) -> DrapedVertex& {
                    return set.vertices[first ? l.first + j : l.first + l.count - 1 - j];
                };
                // vertices whose length is gap / tan 8 degrees
                const double want = plan_length(double(gap[k].x), double(gap[k].y)) / tan_bend;
                std::uint32_t m = 1;
                for (double len = 0.0; m < l.count - 1 && (m < std::uint32_t(ramp) || len < want); ++m)
                    len += plan_length(double(at(m).x) - at(m - 1).x, double(at(m).y) - at(m - 1).y);
                for (std::uint32_t j = 0; j < m; ++j) {
                    const float w = weights(j, m);
                    DrapedVertex& v = at(j);
                    v.x += w * gap[k].x, v.y += w * gap[k].y;
                }
            }
        });
    }
    parallel_chunks(nf, 4096, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k) {
            set.vertices[follow[3 * k + 1]].x = set.vertices[follow[3 * k + 2]].x;
            set.vertices[follow[3 * k + 1]].y = set.vertices[follow[3 * k + 2]].y;
        }
    });
}

// A grid cell's plan length: the mean of a column's and a row's step at the grid's middle.
double grid_cell_length(const DrainageGrid& g) {
    if (g.cols < 2 || g.rows < 2) return 1.0;
    const int c = (g.cols - 2) / 2, r = (g.rows - 2) / 2;
    const glm::dvec2 o = grid_xy(g, c, r), u = grid_xy(g, c + 1, r) - o, v = grid_xy(g, c, r + 1) - o;
    return 0.5 * (plan_length(u.x, u.y) + plan_length(v.x, v.y));
}

// Each stem end that sat on another line's interior vertex (end_matches' triples), after
// tracing: the stem ends at its vertex, among its last `reach`, that comes closest to the line it
// joins (that line's vertices within `reach` of the matched one) when that is within `meet`
// (plan units), its later vertices moved onto it (the tributary stops where its fall line
// reaches its trunk, no overshoot along it); a stem whose trace never comes that close keeps its
// trace to the end (a
// cone's D8 paths merge where its fall lines never do). No vertex is moved sideways: the stem
// keeps its fall line's direction to its end. All ends found first, then moved (the line joined
// may be a stem that ends too).
template <class LineOf>
void end_stems_where_they_meet(DrapedLineSet& set, const std::vector<std::uint32_t>& follow, int reach, double meet,
                               const LineOf& line_of) {
    const std::size_t nf = follow.size() / 3;
    std::vector<std::uint32_t> stop(nf, 0xffffffffu);  // the vertex the stem ends at, none: it keeps its trace
    parallel_chunks(nf, 256, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k) {
            const DrapedLine& l = set.lines[follow[3 * k]];
            const std::uint32_t e = follow[3 * k + 1], t = follow[3 * k + 2];
            if (e != l.first + l.count - 1) continue;  // a stem's first vertex is its source
            const DrapedLine& into = set.lines[line_of[t]];
            const std::int64_t lo = std::max<std::int64_t>(into.first, std::int64_t(t) - reach);
            const std::int64_t hi = std::min<std::int64_t>(std::int64_t(into.first) + into.count - 1, std::int64_t(t) + reach);
            const std::uint32_t from = std::uint32_t(std::max<std::int64_t>(l.first + 1, std::int64_t(e) - reach));
            double closest = meet;  // the closest approach within meet (the first of equals)
            // a squared distance above this one's square root exceeds `closest` (the bound's
            // 1e-9 lies far above sqrt's rounding): skipped without the square root
            double beyond = closest * closest * (1.0 + 1e-9);
            // the boxes of the joined line's vertices in groups of 4: a group whose box's squared
            // distance to a vertex (the same roundings, each no larger than to any vertex inside)
            // exceeds `beyond` lies farther from it with all its vertices, skipped without them
            constexpr std::int64_t group = 4;
            struct Box {
                float x0, x1, y0, y1;
            };
            Box boxes[64];
            const std::int64_t ng = std::min<std::int64_t>((hi - lo + group) / group, 64);
            if (ng <= 0) continue;  // t lies in `into`, so lo <= t <= hi: never, but boxes[0] is read below
            // the squared distance from v to a box (0 inside; each difference no larger than v's
            // to any vertex in it, so neither its square nor the sum)
            auto box_distance2 = [](const Box& b, const DrapedVertex& v) {
                const double bx = std::max(std::max(double(b.x0) - v.x, 0.0), v.x - double(b.x1));
                const double by = std::max(std::max(double(b.y0) - v.y, 0.0), v.y - double(b.y1));
                return bx * bx + by * by;
            };
            for (std::int64_t g = 0; g < ng; ++g) {
                const std::int64_t j0 = lo + g * group, j1 = g + 1 == ng ? hi : std::min(hi, j0 + group - 1);
                Box& b = boxes[g];
                b = {set.vertices[j0].x, set.vertices[j0].x, set.vertices[j0].y, set.vertices[j0].y};
                for (std::int64_t j = j0 + 1; j <= j1; ++j) {
                    b.x0 = std::min(b.x0, set.vertices[j].x), b.x1 = std::max(b.x1, set.vertices[j].x);
                    b.y0 = std::min(b.y0, set.vertices[j].y), b.y1 = std::max(b.y1, set.vertices[j].y);
                }
            }
            Box all = boxes[0];  // the whole window's: a vertex beyond it skips every group
            for (std::int64_t g = 1; g < ng; ++g)
                all = {std::min(all.x0, boxes[g].x0), std::max(all.x1, boxes[g].x1), std::min(all.y0, boxes[g].y0),
                       std::max(all.y1, boxes[g].y1)};
            // from the end back (a trace's last vertices come closest: the bound shrinks early), a
            // distance equal to the closest taking the earlier vertex: the first of equals
            for (std::uint32_t i = e + 1; i-- > from;) {
                const DrapedVertex& v = set.vertices[i];
                if (box_distance2(all, v) > beyond) continue;
                for (std::int64_t g = 0; g < ng; ++g) {
                    if (box_distance2(boxes[g], v) > beyond) continue;
                    const std::int64_t j0 = lo + g * group, j1 = g + 1 == ng ? hi : std::min(hi, j0 + group - 1);
                    for (std::int64_t j = j0; j <= j1; ++j) {
                        const double dx = double(set.vertices[j].x) - v.x, dy = double(set.vertices[j].y) - v.y;
                        if (dx * dx + dy * dy > beyond) continue;
                        const double d = plan_length(dx, dy);
                        if (d <= closest) closest = d, stop[k] = i, beyond = closest * closest * (1.0 + 1e-9);
                    }
                }
            }
        }
    });
    parallel_chunks(nf, 4096, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k) {
            if (stop[k] == 0xffffffffu) continue;
            const DrapedVertex at = set.vertices[stop[k]];
            for (std::uint32_t i = stop[k] + 1; i <= follow[3 * k + 1]; ++i) set.vertices[i].x = at.x, set.vertices[i].y = at.y;
        }
    });
}

}  // namespace

namespace {

// Where the walks of stems may end before their ends: stem s (its place in the sources walked)
// ends `after` vertices past the last of the left[s] cells mapped to s in `cells` (cell -> s; each
// passed once), or at its end when it passes fewer (left[s] 0: at its end).
struct WalkReach {
    U32Map cells;
    std::vector<std::uint32_t> left;
    std::uint32_t after = 0;
};

// The stems starting at `sources` (cells), in that order, each walked by `walk` (network_stems'
// layout), to their ends or where `reach` ends them; `cells`, when given, gets each vertex's grid
// cell.
DrapedLineSet walk_stems(const StemWalk& walk, const DrainageGrid& g, const std::vector<std::uint32_t>& sources,
                         std::vector<std::uint32_t>* cells, const WalkReach* reach = nullptr) {
    DrapedLineSet set;
    set.lines.resize(sources.size());
    // Every cell is walked by one stem, whose end junction is its last vertex and may be another
    // stem's cell: at most the cells and one end a stem. One walk a stem, in blocks of sources:
    // each chunk of a block into its own buffers, then the buffers copied into place.
    const std::size_t bound = g.size() + sources.size();
    if (bound > 0xffffffffull)
        throw Error("drainage", "", "too many stem vertices for the database (4 G or more)", ExitCode::internal);
    // a part's stems (fewer than one an 8 cells): as many vertices as they hold, grown per block,
    // not the grid's cells
    const bool whole = sources.size() * 8 >= g.size();
    set.vertices.resize(whole ? bound : 0);
    if (cells) cells->resize(whole ? bound : 0);
    // (a part's stems, a tile's few thousand at most, in chunks of 64 or more: on all cores too)
    constexpr std::size_t block = std::size_t(1) << 16;
    const std::size_t min_chunk = whole ? 1024 : 64;
    struct Buffer {
        std::vector<DrapedVertex> v;
        std::vector<std::uint32_t> c;
        std::size_t at = 0;
    };
    std::vector<Buffer> buffer(17);  // parallel_chunks makes at most 16 chunks
    std::uint64_t next = 0;
    for (std::size_t b0 = 0; b0 < sources.size(); b0 += block) {
        const std::size_t n = std::min(block, sources.size() - b0), per = chunk_length(n, min_chunk);
        parallel_chunks(n, min_chunk, [&](std::size_t s0, std::size_t s1) {
            Buffer& out = buffer[s0 / per];
            out.v.clear(), out.c.clear();
            for (std::size_t s = b0 + s0; s < b0 + s1; ++s) {
                const std::size_t before = out.v.size();
                std::uint32_t left = reach ? reach->left[s] : 0, past = 0;
                set.lines[s].order = walk.walk(sources[s], [&](const DvVertex& v, std::size_t c) {
                    out.v.push_back(draped(v));
                    if (cells) out.c.push_back(std::uint32_t(c));
                    if (past) return --past > 0;
                    if (left)
                        if (const std::uint32_t* at = reach->cells.find(std::uint32_t(c)); at && *at == s && --left == 0)
                            past = reach->after;
                    return true;
                });
                set.lines[s].count = std::uint32_t(out.v.size() - before);
            }
        });
        for (std::size_t s = b0; s < b0 + n; ++s) {
            DrapedLine& l = set.lines[s];
            if ((s - b0) % per == 0) buffer[(s - b0) / per].at = std::size_t(next);
            if (next > bound - l.count)
                throw Error("drainage", "", "stems hold more vertices than the grid has cells", ExitCode::internal);
            l.first = std::uint32_t(next), next += l.count;
        }
        if (!whole) {
            set.vertices.resize(std::size_t(next));
            if (cells) cells->resize(std::size_t(next));
        }
        parallel_chunks(n, min_chunk, [&](std::size_t s0, std::size_t) {
            const Buffer& in = buffer[s0 / per];
            std::copy(in.v.begin(), in.v.end(), set.vertices.begin() + std::ptrdiff_t(in.at));
            if (cells) std::copy(in.c.begin(), in.c.end(), cells->begin() + std::ptrdiff_t(in.at));
        });
    }
    set.vertices.resize(std::size_t(next));
    if (cells) cells->resize(std::size_t(next));
    return set;
}

std::vector<std::uint32_t> sources_of(const StemWalk& walk, const DrainageGrid& g) {
    return parallel_collect<std::uint32_t>(g.size(), 1 << 16, [&](std::size_t i0, std::size_t i1, std::vector<std::uint32_t>& out) {
        for (std::size_t i = i0; i < i1; ++i)
            if (g.valid[i] && walk.indeg[i] == 0) out.push_back(std::uint32_t(i));
    });
}

}  // namespace

std::vector<std::uint64_t> main_upstream_bits(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                              const FlowNetwork& net) {
    const StemWalk walk(g, dir, net);
    std::vector<std::uint64_t> bits(mains_words(g.size()), 0);
    // rows in order on all cores (a main cell may lie in another chunk's row: its word set
    // atomically)
    parallel_chunks(std::size_t(g.rows), 16, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t d = r0 * std::size_t(g.cols); d < r1 * std::size_t(g.cols); ++d) {
            if (walk.indeg[d] < 2) continue;  // no junction
            const std::size_t m = walk.main_upstream(d);
            if (m != d)
                std::atomic_ref<std::uint64_t>(bits[m >> 6]).fetch_or(std::uint64_t(1) << (m & 63), std::memory_order_relaxed);
        }
    });
    return bits;
}

StemParts stem_parts(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net) {
    const StemWalk walk(g, dir, net);
    StemParts out;
    out.sources = sources_of(walk, g);
    // every valid cell is a vertex of the stem through it (or a junction ending one): the box of
    // their plan positions (walk.xy, as walk.vertex gives them), rows on all cores (min and max:
    // the same box in any order)
    const std::vector<std::array<glm::vec2, 2>> boxes =
        parallel_collect<std::array<glm::vec2, 2>>(std::size_t(g.rows), 16, [&](std::size_t r0, std::size_t r1, auto& o) {
            glm::vec2 lo(std::numeric_limits<float>::infinity()), hi = -lo;
            for (std::size_t i = r0 * std::size_t(g.cols); i < r1 * std::size_t(g.cols); ++i)
                if (g.valid[i]) {
                    const glm::vec2 v = walk.xy(i);
                    lo = glm::min(lo, v), hi = glm::max(hi, v);
                }
            o.push_back({lo, hi});
        });
    out.lo = glm::vec2(std::numeric_limits<float>::infinity()), out.hi = -out.lo;
    for (const auto& b : boxes) out.lo = glm::min(out.lo, b[0]), out.hi = glm::max(out.hi, b[1]);
    return out;
}

void for_each_stem_cells(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                         const StemParts& parts,
                         const std::function<void(std::size_t, std::uint32_t, const std::uint32_t*, const glm::vec2*, std::uint32_t)>& f,
                         const std::vector<std::size_t>& cuts, const std::function<void(std::size_t)>& done) {
    StemWalk walk(g, dir, net);
    walk.use_mains(true);  // every stem walked: each junction's main found once
    const std::vector<std::size_t> whole{0, parts.sources.size()};
    const std::vector<std::size_t>& at = cuts.empty() ? whole : cuts;
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
        const std::size_t first = at[k], n = at[k + 1] - first, per = chunk_length(n, 1024);  // at most 16 chunks
        parallel_chunks(n, 1024, [&](std::size_t s0, std::size_t s1) {
            std::vector<std::uint32_t> cells;
            std::vector<glm::vec2> xy;
            for (std::size_t s = first + s0; s < first + s1; ++s) {
                cells.clear(), xy.clear();
                walk.walk(parts.sources[s], [&](const DvVertex& v, std::size_t c) {
                    cells.push_back(std::uint32_t(c)), xy.emplace_back(v.x, v.y);
                });
                f(s0 / per, std::uint32_t(s), cells.data(), xy.data(), std::uint32_t(cells.size()));
            }
        });
        if (done) done(k);
    }
}

DrapedLineSet network_stems(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                            std::vector<std::uint32_t>* cells) {
    const StemWalk walk(g, dir, net);
    return walk_stems(walk, g, sources_of(walk, g), cells);
}

DrapedLineSet listed_lines(const DvVertices& vertices, const std::vector<std::vector<std::uint32_t>>& lines) {
    DrapedLineSet set;
    std::size_t n = 0;
    for (const auto& line : lines) n += line.size();
    set.vertices.resize(n);
    std::size_t at = 0;
    for (const auto& line : lines) {
        DrapedLine l;
        l.first = std::uint32_t(at), l.count = std::uint32_t(line.size());
        for (std::uint32_t i : line) set.vertices[at++] = draped(vertices[i]);
        if (l.count) set.lines.push_back(l);
    }
    return set;
}

namespace {

// Step 2 with the end matches `follow` (end_matches' triples) and the box [lo, hi] given.
void smooth_lines_joined(DrapedLineSet& set, double sigma, const std::vector<std::uint32_t>& follow, glm::vec2 lo,
                         glm::vec2 hi) {
    smooth_each_line(set, sigma);
    join_ends(set, follow, int(std::ceil(3.0 * sigma)));
    clamp_to_box(set, lo, hi);
}
// The vertices before and after a junction's that a stem ending there is measured against, and of
// its own last ones those it may end at (end_stems_where_they_meet's `reach`): 4 corridors.
int stem_end_reach(const FallLineOptions& options) { return int(std::ceil(4.0 * options.corridor)); }

// Step 2 for stems once traced (trace_fall_lines): their ends (`follow`: end_matches' triples)
// where they meet the lines they join, then the box [lo, hi].
void end_traced_stems(DrapedLineSet& set, const DrainageGrid& g, const FallLineOptions& options,
                      const std::vector<std::uint32_t>& follow, glm::vec2 lo, glm::vec2 hi) {
    end_stems_where_they_meet(set, follow, stem_end_reach(options), options.meet * grid_cell_length(g), line_ids(set));
    clamp_to_box(set, lo, hi);
}

void smooth_stems_joined(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                         const FallLineOptions& options, const std::vector<std::uint32_t>& follow, glm::vec2 lo,
                         glm::vec2 hi) {
    trace_fall_lines(set, cells, g, options);
    end_traced_stems(set, g, options, follow, lo, hi);
}

// The end matches among `set`'s lines, which are the whole set's lines `ids` (in that order), as
// end_matches' triples: the joins of each line whose joined line is among them, in line order.
std::vector<std::uint32_t> part_follow(const DrapedLineSet& set, const LineJoins& joins,
                                       const std::vector<std::uint32_t>& ids) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> local(ids.size());  // (whole id, local id)
    for (std::size_t i = 0; i < ids.size(); ++i) local[i] = {ids[i], std::uint32_t(i)};
    std::sort(local.begin(), local.end());
    auto find = [&](std::uint32_t id) -> std::uint32_t {
        const auto it = std::lower_bound(local.begin(), local.end(), std::pair<std::uint32_t, std::uint32_t>(id, 0));
        return it != local.end() && it->first == id ? it->second : EndMatches::none;
    };
    std::vector<std::uint32_t> follow;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const DrapedLine& l = set.lines[i];
        for (std::uint32_t k = joins.start[ids[i]]; k < joins.start[ids[i] + 1]; ++k) {
            const LineJoin& j = joins.joins[k];
            const std::uint32_t into = find(j.into);
            if (into == EndMatches::none) continue;
            if (j.offset >= set.lines[into].count || l.count < 2)
                throw Error("drainage", "", "line joins do not fit the lines", ExitCode::internal);
            follow.push_back(std::uint32_t(i)), follow.push_back(j.last ? l.first + l.count - 1 : l.first);
            follow.push_back(set.lines[into].first + j.offset);
        }
    }
    return follow;
}

// The first n lines of a set whose lines lie in order from vertex 0.
void keep_first_lines(DrapedLineSet& set, std::size_t n) {
    if (n >= set.lines.size()) return;
    set.vertices.resize(n ? std::size_t(set.lines[n - 1].first) + set.lines[n - 1].count : 0);
    set.lines.resize(n);
}

}  // namespace

void smooth_lines(DrapedLineSet& set, double sigma) {
    const std::vector<std::uint32_t> follow = end_matches(set);
    glm::vec2 lo, hi;
    vertex_box(set, lo, hi);
    smooth_lines_joined(set, sigma, follow, lo, hi);
}

void smooth_stems(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                  const FallLineOptions& options) {
    const std::vector<std::uint32_t> follow = end_matches(set);
    glm::vec2 lo, hi;
    vertex_box(set, lo, hi);
    smooth_stems_joined(set, cells, g, options, follow, lo, hi);
}

LineJoins line_joins(const DrapedLineSet& set) {
    LineJoins out;
    vertex_box(set, out.lo, out.hi);
    const std::vector<std::uint32_t> follow = end_matches(set);  // in line order, first end first
    const auto line_of = line_ids(set);
    out.start.assign(set.lines.size() + 1, 0);
    out.joins.reserve(follow.size() / 3);
    for (std::size_t k = 0; k < follow.size(); k += 3) {
        const DrapedLine& l = set.lines[follow[k]];
        const std::uint32_t into = line_of[follow[k + 2]];
        out.joins.push_back({follow[k], follow[k + 1] == l.first ? 0u : 1u, into, follow[k + 2] - set.lines[into].first});
        ++out.start[follow[k] + 1];
    }
    for (std::size_t l = 0; l < set.lines.size(); ++l) out.start[l + 1] += out.start[l];
    return out;
}

std::vector<std::uint32_t> join_closure(const LineJoins& joins, const std::vector<std::uint32_t>& ids, int depth) {
    std::vector<std::uint8_t> seen(joins.start.size() - 1, 0);
    for (std::uint32_t id : ids) seen.at(id) = 1;
    std::vector<std::uint32_t> level = ids, added;
    for (int d = 0; d < depth && !level.empty(); ++d) {
        std::vector<std::uint32_t> next;
        for (std::uint32_t id : level)
            for (std::uint32_t k = joins.start[id]; k < joins.start[id + 1]; ++k)
                if (const std::uint32_t into = joins.joins[k].into; !seen[into]) seen[into] = 1, next.push_back(into);
        added.insert(added.end(), next.begin(), next.end());
        level = std::move(next);
    }
    std::sort(added.begin(), added.end());
    std::vector<std::uint32_t> out = ids;
    out.insert(out.end(), added.begin(), added.end());
    return out;
}

LineLattice crease_lattice(const DrainageGrid& g) { return line_lattice(std::min(g.dx, g.dy)); }

DrapedLineSet crease_part(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                          const DemSurface& surface, const StemParts& parts, const std::vector<std::uint32_t>& ids) {
    StemWalk walk(g, dir, net);
    walk.use_mains(false);  // the network's, where it has them (a part's stems alone: not found here)
    std::vector<std::uint32_t> own(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) own[i] = parts.sources.at(ids[i]);
    // a stem's end reads its trunk's trace, which reads nothing of other stems: one level
    std::vector<std::uint32_t> cells;
    DrapedLineSet set = walk_stems(walk, g, own, &cells);
    const FallLineOptions options = fall_line_options(g);
    // the part's own stems traced beside finding, walking and tracing their trunks (a stem's
    // trace reads its own vertices alone: the same as in one set)
    std::vector<std::uint32_t> trunk(ids.size()), closure = own, added;
    DrapedLineSet trunks;
    std::vector<std::uint32_t> trunk_cells;
    run_beside([&] { trace_fall_lines(set, cells, g, options); }, [&] {
        // the source of the stem each joins (its own: none), up from its end junction; the
        // junctions climbed remembered with their source (the tributaries of one trunk climb it
        // once; a climb meets a climbed stem at a junction, where another stem joins it)
        U32Map climbed;
        std::vector<std::uint32_t> path;
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const DrapedLine& l = set.lines[i];
            if (l.count < 2) {
                trunk[i] = own[i];
                continue;
            }
            std::size_t m = cells[l.first + l.count - 1];
            path.clear();
            std::uint32_t source;
            for (std::size_t steps = 0;; ++steps) {
                walk.need(m);
                const bool junction = walk.indeg[m] > 1;
                if (const std::uint32_t* at = junction ? climbed.find(std::uint32_t(m)) : nullptr) {
                    source = *at;
                    break;
                }
                const std::size_t up = walk.main_up(m);
                if (up == m) {
                    source = std::uint32_t(m);
                    break;
                }
                if (steps > g.size()) StemWalk::cycle();
                if (junction) path.push_back(std::uint32_t(m));
                m = up;
            }
            for (std::uint32_t c : path) climbed.insert(c, source);
            trunk[i] = source;
        }
        {
            std::vector<std::uint32_t> sorted_own = own;
            std::sort(sorted_own.begin(), sorted_own.end());
            for (std::size_t i = 0; i < ids.size(); ++i)
                if (trunk[i] != own[i] && !std::binary_search(sorted_own.begin(), sorted_own.end(), trunk[i]))
                    added.push_back(trunk[i]);
            std::sort(added.begin(), added.end());
            added.erase(std::unique(added.begin(), added.end()), added.end());
            closure.insert(closure.end(), added.begin(), added.end());
        }
        // the trunks walked after the part's own stems, each as far as its trace is read: past the
        // last junction its tributaries here end at by end_stems_where_they_meet's reach and the
        // smoothing's radius (a trace's vertex reads the smoothed path up to it, which reads the
        // cells a radius on), two more spare
        WalkReach reach;
        reach.left.assign(added.size(), 0);
        reach.after = std::uint32_t(stem_end_reach(options) + GaussianKernel(options.sigma).radius() + 2);
        for (std::size_t i = 0; i < ids.size(); ++i) {
            if (trunk[i] == own[i]) continue;
            const auto a = std::lower_bound(added.begin(), added.end(), trunk[i]);
            if (a == added.end() || *a != trunk[i]) continue;  // one of the part's own stems: walked whole
            const DrapedLine& l = set.lines[i];
            if (reach.cells.insert(cells[l.first + l.count - 1], std::uint32_t(a - added.begin())))
                ++reach.left[std::size_t(a - added.begin())];
        }
        trunks = walk_stems(walk, g, added, &trunk_cells, &reach);
        trace_fall_lines(trunks, trunk_cells, g, options);
    });
    {
        const auto at = std::uint32_t(set.vertices.size());
        set.vertices.insert(set.vertices.end(), trunks.vertices.begin(), trunks.vertices.end());
        cells.insert(cells.end(), trunk_cells.begin(), trunk_cells.end());
        for (DrapedLine l : trunks.lines) l.first += at, set.lines.push_back(l);
    }
    // the joins: each stem's last vertex follows its trunk's interior vertex at the junction cell
    std::vector<std::pair<std::uint32_t, std::uint32_t>> local(closure.size());  // (source, line)
    for (std::size_t i = 0; i < closure.size(); ++i) local[i] = {closure[i], std::uint32_t(i)};
    std::sort(local.begin(), local.end());
    std::vector<std::uint32_t> into_line(ids.size(), EndMatches::none);
    std::vector<std::uint8_t> is_trunk(closure.size(), 0);
    U32Map junction;  // the junction cells the stems end at -> their slot in `interior`
    for (std::size_t i = 0; i < ids.size(); ++i)
        if (trunk[i] != own[i]) {
            into_line[i] = std::lower_bound(local.begin(), local.end(), std::pair<std::uint32_t, std::uint32_t>(trunk[i], 0))->second;
            is_trunk[into_line[i]] = 1;
            const DrapedLine& l = set.lines[i];
            junction.insert(cells[l.first + l.count - 1], std::uint32_t(junction.size()));
        }
    // the trunks' first interior vertex at each of those cells (a stem walks a cell once)
    std::vector<std::uint32_t> interior(junction.size(), EndMatches::none);
    for (std::size_t t = 0; t < closure.size(); ++t)
        if (is_trunk[t])
            for (std::uint32_t k = 1; k + 1 < set.lines[t].count; ++k)
                if (const std::uint32_t* j = junction.find(cells[set.lines[t].first + k]); j && interior[*j] == EndMatches::none)
                    interior[*j] = set.lines[t].first + k;
    std::vector<std::uint32_t> follow;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        if (into_line[i] == EndMatches::none) continue;
        const DrapedLine& l = set.lines[i];
        const std::uint32_t end = l.first + l.count - 1;
        const std::uint32_t at = interior[*junction.find(cells[end])];
        if (at == EndMatches::none) continue;  // the trunk ends there too (an outlet): no interior to follow
        const DrapedLine& into = set.lines[into_line[i]];
        if (at < into.first || at >= into.first + into.count) continue;
        follow.push_back(std::uint32_t(i)), follow.push_back(end), follow.push_back(at);
    }
    end_traced_stems(set, g, options, follow, parts.lo, parts.hi);
    keep_first_lines(set, ids.size());
    const DrapeLattice lattice{crease_lattice(g), parts.lo, parts.hi};
    drape_lines(set, surface, {}, &lattice);
    return set;
}

DrapedLineSet ridge_part(const DrainageGrid& g, const DemSurface& surface, const DrapedLineSet& listed,
                         const LineJoins& joins, const std::vector<std::uint32_t>& ids) {
    // join_ends' three rounds and its final snap each read the joined line as the round before
    // left it: a line's result reads lines up to four joins away
    const std::vector<std::uint32_t> closure = join_closure(joins, ids, 4);
    DrapedLineSet set;
    std::size_t n = 0;
    for (std::uint32_t id : closure) n += listed.lines.at(id).count;
    set.vertices.resize(n);
    set.lines.reserve(closure.size());
    std::size_t at = 0;
    for (std::uint32_t id : closure) {
        DrapedLine l = listed.lines[id];
        std::copy_n(listed.vertices.begin() + l.first, l.count, set.vertices.begin() + std::ptrdiff_t(at));
        l.first = std::uint32_t(at), at += l.count;
        set.lines.push_back(l);
    }
    smooth_lines_joined(set, 3.0 * fall_line_options(g).sigma, part_follow(set, joins, closure), joins.lo, joins.hi);
    keep_first_lines(set, ids.size());
    snap_to_crests(set, surface, crest_options(g));
    drape_lines(set, surface);
    return set;
}

void drape_lines(DrapedLineSet& set, const DemSurface& surface, const LineProgress& progress,
                 const DrapeLattice* lattice) {
    // In batches of lines so the progress moves (one batch without progress: a crease part's few
    // vertices in 16 batches would leave each below a chunk, on one core), batches and the
    // threads' chunks of equal shares of the vertices (line_chunks.hpp); each thread walks its
    // lines with the cell of the vertex before as the next one's start.
    const std::size_t batches = progress ? 16 : 1;
    const std::size_t nl = set.lines.size(), nv = set.vertices.size();
    for (std::size_t b = 0, l0 = 0; b < batches && l0 < nl; ++b) {
        const std::size_t l1 = b + 1 == batches ? nl : std::max(l0 + 1, line_at(set.lines, (b + 1) * nv / batches));
        parallel_line_chunks(set.lines, nv, l0, l1, 4096, [&](std::size_t i0, std::size_t i1) {
            const DemDraper draper(surface);
            // the located vertices evaluated four at a time (height_normal4: the same floats)
            DemHit hits[4];
            DrapedVertex* at[4];
            int pending = 0;
            auto evaluate = [&] {
                float z[4];
                glm::vec3 n[4];
                if (pending == 4) draper.height_normal4(hits, z, n);
                else
                    for (int j = 0; j < pending; ++j) z[j] = draper.height_normal(hits[j], n[j]);
                for (int j = 0; j < pending; ++j) {
                    at[j]->z = z[j], at[j]->nx = n[j].x, at[j]->ny = n[j].y, at[j]->nz = n[j].z;
                    if (lattice) *at[j] = snapped_vertex(*at[j], lattice->lattice, lattice->lo, lattice->hi);
                }
                pending = 0;
            };
            for (std::size_t i = i0; i < i1; ++i) {
                const DrapedLine& l = set.lines[i];
                int c = -1, r = -1;
                for (std::uint32_t k = 0; k < l.count; ++k) {
                    DrapedVertex& v = set.vertices[l.first + k];
                    if (lattice) v = snapped_vertex(v, lattice->lattice, lattice->lo, lattice->hi);  // draped where it lies
                    if (!draper.locate(v.x, v.y, c, r, hits[pending])) {
                        v.nx = v.ny = v.nz = 0.0f;
                        continue;
                    }
                    at[pending++] = &v;
                    if (pending == 4) evaluate();
                }
            }
            evaluate();
        });
        l0 = l1;
        if (progress) progress(double(l1) / double(nl));
    }
    index_lines(set);
    if (progress) progress(1.0);
}

void smooth_and_drape(DrapedLineSet& set, const DemSurface& surface, const LineProgress& progress) {
    smooth_lines(set);
    drape_lines(set, surface, progress);
}

bool has_relief(const DrainageGrid& g) {
    // the DEM's own heights: the coarse nodes' at factor > 1 (the resampled surface may round)
    const bool coarse = !g.coarse_z.empty();
    const std::vector<float>& z = coarse ? g.coarse_z : g.z;
    const std::vector<std::uint8_t>& valid = coarse ? g.coarse_valid : g.valid;
    // per chunk on all cores: whether any valid height differs from the chunk's first
    const std::size_t n = std::min(z.size(), valid.size());
    struct Span {
        bool any = false;
        float lo = 0.0f, hi = 0.0f;
    };
    const std::vector<Span> spans = parallel_collect<Span>(n, 1 << 16, [&](std::size_t i0, std::size_t i1, std::vector<Span>& out) {
        Span s;
        for (std::size_t i = i0; i < i1; ++i) {
            if (!valid[i]) continue;
            if (!s.any) s.lo = s.hi = z[i], s.any = true;
            s.lo = std::min(s.lo, z[i]), s.hi = std::max(s.hi, z[i]);
        }
        out.push_back(s);
    });
    bool any = false;
    float lo = 0.0f, hi = 0.0f;
    for (const Span& s : spans) {
        if (!s.any) continue;
        if (!any) lo = s.lo, hi = s.hi, any = true;
        lo = std::min(lo, s.lo), hi = std::max(hi, s.hi);
    }
    return any && hi > lo;
}

namespace {

// Steps 1 and 2 for the divides of db (empty on a DEM without relief).
void smoothed_ridges(const DrainageGrid& g, DrainageDb& db) {
    db.ridges = listed_lines(db.divide_vertices, divide_polylines(db));
    smooth_lines(db.ridges, 3.0 * fall_line_options(g).sigma);
    if (!has_relief(g)) db.ridges.lines.clear(), db.ridges.vertices.clear();
}

}  // namespace

void build_draped_ridges(const DrainageGrid& g, DrainageDb& db, const LineProgress& progress,
                         const DemSurface* surface) {
    smoothed_ridges(g, db);
    std::optional<DemSurface> own;  // normals made where the ridges need them: a few of the nodes
    if (!surface) surface = &own.emplace(g, DemSurface::Normals::on_demand);
    snap_to_crests(db.ridges, *surface, crest_options(g));
    drape_lines(db.ridges, *surface, progress);
}

void build_draped_lines(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                        DrainageDb& db, const LineProgress& progress) {
    auto report = [&](double f) {
        if (progress) progress(f);
    };
    // smoothing (its table of line ends) before the surface's normals: never both in memory
    DrapeLattice lattice{crease_lattice(g), {}, {}};
    {
        std::vector<std::uint32_t> cells;
        db.creases = network_stems(g, dir, net, &cells);
        vertex_box(db.creases, lattice.lo, lattice.hi);  // what smooth_stems clamps to
        report(0.05);
        smooth_stems(db.creases, cells, g, fall_line_options(g));
    }
    report(0.1);
    smoothed_ridges(g, db);
    report(0.15);
    if (!has_relief(g))  // a plane: its network follows only the tie-breaking of flats; nothing to draw
        db.creases.lines.clear(), db.creases.vertices.clear();
    const DemSurface surface(g);
    snap_to_crests(db.ridges, surface, crest_options(g));
    report(0.2);
    const double nc = double(db.creases.vertices.size()), nr = double(db.divide_vertices.size());
    const double share = nc + nr > 0.0 ? nc / (nc + nr) : 1.0;
    drape_lines(db.creases, surface, [&](double f) { report(0.2 + 0.8 * share * f); }, &lattice);
    drape_lines(db.ridges, surface, [&](double f) { report(0.2 + 0.8 * (share + (1.0 - share) * f)); });
}

}  // namespace penink
