#include "drainage/draped_lines.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/d8.hpp"
#include "drainage/stems.hpp"
#include "drainage/fall_line_stems.hpp"
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
    std::vector<std::uint8_t> own_indeg;
    const std::vector<std::uint8_t>& indeg;
    std::vector<double> total;  // accumulation at each basin's outlet

    StemWalk(const DrainageGrid& grid, const std::vector<std::uint8_t>& d, const FlowNetwork& n)
        : g(grid), dir(d), net(n),
          own_indeg(n.indeg.size() == grid.size() ? std::vector<std::uint8_t>() : inflow_counts(d, shape)),
          indeg(own_indeg.empty() ? n.indeg : own_indeg) {
        total.resize(net.outlet.size());
        for (std::size_t b = 0; b < total.size(); ++b) total[b] = net.acc[net.outlet[b]];
    }
    StemWalk(const StemWalk&) = delete;

    // The drainage vertex of cell i (build_branches' point_vertex).
    DvVertex vertex(std::size_t i) const {
        const glm::dvec2 p = grid_xy(g, int(i % std::size_t(g.cols)), int(i / std::size_t(g.cols)));
        return {float(p.x), float(p.y), g.z[i], float(double(net.acc[i]) / total[net.basin[i] - 1])};
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
        for (std::size_t steps = 0; indeg[m] == 1; ++steps) {
            if (steps > g.size()) cycle();
            std::size_t up = m;
            each_upstream(m, [&](std::size_t u) { up = u; });
            m = up;
        }
        return m;
    }

    // Whether the branch arriving at junction d through cell n is d's main upstream branch
    // (stems.cpp main_upstream: highest order, then larger flow just above the junction, then
    // the lower branch id).
    bool main_into(std::size_t n, std::size_t d) const {
        struct Candidate {
            std::size_t cell;
            std::uint8_t order;
            float flow;
        };
        Candidate c[8];
        int k = 0, best = -1;
        each_upstream(d, [&](std::size_t m) {
            c[k] = {m, net.order[m], vertex_flow(m)};
            if (best < 0 || c[k].order > c[best].order || (c[k].order == c[best].order && c[k].flow > c[best].flow))
                best = k;
            ++k;
        });
        bool tied_with_n = false;
        int others = 0;
        for (int i = 0; i < k; ++i) {
            const bool tied = c[i].order == c[best].order && c[i].flow == c[best].flow;
            if (!tied) continue;
            if (c[i].cell == n) tied_with_n = true;
            else ++others;
        }
        if (!tied_with_n) return false;
        if (others == 0) return true;
        const std::size_t own = head(n);
        for (int i = 0; i < k; ++i)
            if (c[i].cell != n && c[i].order == c[best].order && c[i].flow == c[best].flow && head(c[i].cell) < own)
                return false;
        return true;
    }

    float vertex_flow(std::size_t i) const { return float(double(net.acc[i]) / total[net.basin[i] - 1]); }

    [[noreturn]] static void cycle() {
        throw Error("drainage", "", "flow directions contain a cycle (stem without an end)", ExitCode::internal);
    }

    // Emits the cells of the stem starting at `source` (emit(vertex, cell)), dropping a vertex at
    // the x, y of the one before it (drainage_stems' shared junction rule); returns the stem's order.
    template <class Emit> std::uint8_t walk(std::size_t source, Emit&& emit) const {
        std::uint8_t order = 0;
        DvVertex last{};
        bool any = false;
        auto put = [&](std::size_t c) {
            const DvVertex v = vertex(c);
            if (any && last.x == v.x && last.y == v.y) return;
            emit(v, c), last = v, any = true;
        };
        std::size_t c = source;
        for (std::size_t steps = 0; steps <= g.size(); ++steps) {
            put(c);
            order = std::max(order, net.order[c]);
            if (!dir[c]) return order;
            const std::size_t d = d8_target(shape, c, dir[c]);
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
// with the first interior vertex (in line order) at the same x, y: rejoin_line_ends' matches,
// found before smoothing.
class EndMatches {
public:
    explicit EndMatches(const DrapedLineSet& set) {
        std::size_t ends = 0;
        for (const DrapedLine& l : set.lines) ends += l.count >= 2 ? 2 : 0;
        key_.assign(std::max<std::size_t>(16, ends + ends / 2), empty);
        first_.assign(key_.size(), none);
        for (const DrapedLine& l : set.lines)
            if (l.count >= 2)
                for (std::uint32_t e : {l.first, l.first + l.count - 1}) insert(xy_key(set.vertices[e]));
        // interior vertices (lines of 3 or more), on all cores; the least index wins
        parallel_chunks(set.lines.size(), 4096, [&](std::size_t l0, std::size_t l1) {
            for (std::size_t i = l0; i < l1; ++i) {
                const DrapedLine& l = set.lines[i];
                for (std::uint32_t k = 1; k + 1 < l.count; ++k) {
                    const std::size_t s = find(xy_key(set.vertices[l.first + k]));
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

    std::size_t slot(std::uint64_t k) const {
        k ^= k >> 31, k *= 0x7fb5d329728ea185ull, k ^= k >> 27, k *= 0x81dadef4bc2dd44dull, k ^= k >> 33;
        return std::size_t((unsigned __int128)k * key_.size() >> 64);
    }
    void insert(std::uint64_t k) {
        if (k == empty) return;
        std::size_t s = slot(k);
        while (key_[s] != empty && key_[s] != k) s = s + 1 == key_.size() ? 0 : s + 1;
        key_[s] = k;
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

// The plan box of a set's vertices.
void vertex_box(const DrapedLineSet& set, glm::vec2& lo, glm::vec2& hi) {
    lo = glm::vec2(std::numeric_limits<float>::infinity()), hi = -lo;
    for (const DrapedVertex& v : set.vertices)
        lo = glm::min(lo, glm::vec2(v.x, v.y)), hi = glm::max(hi, glm::vec2(v.x, v.y));
}

// Every vertex's x, y clamped to [lo, hi]: smoothed lines stay inside the box the network's own
// vertices span (inside the DEM's, which a frame cuts lines to).
void clamp_to_box(DrapedLineSet& set, glm::vec2 lo, glm::vec2 hi) {
    if (!(lo.x <= hi.x && lo.y <= hi.y)) return;
    for (DrapedVertex& v : set.vertices) v.x = std::clamp(v.x, lo.x, hi.x), v.y = std::clamp(v.y, lo.y, hi.y);
}

// The line holding each vertex.
std::vector<std::uint32_t> line_ids(const DrapedLineSet& set) {
    std::vector<std::uint32_t> out(set.vertices.size());
    for (std::uint32_t i = 0; i < set.lines.size(); ++i)
        std::fill_n(out.begin() + set.lines[i].first, set.lines[i].count, i);
    return out;
}

// rejoin_line_ends' matches of the set as it is: (line, end vertex, interior vertex) triples.
std::vector<std::uint32_t> end_matches(const DrapedLineSet& set) {
    std::vector<std::uint32_t> follow;
    const EndMatches matches(set);
    for (std::uint32_t i = 0; i < set.lines.size(); ++i) {
        const DrapedLine& l = set.lines[i];
        if (l.count >= 2)
            for (std::uint32_t e : {l.first, l.first + l.count - 1})
                if (const std::uint32_t t = matches.target(set.vertices[e]); t != EndMatches::none)
                    follow.push_back(i), follow.push_back(e), follow.push_back(t);
    }
    return follow;
}

// Each matched end brought to its line's new x, y: first its target slides along the line it
// joins to that line's vertex nearest the end, within `window` vertices of the matched one and
// on the same line (the junction keeps its two lines and moves along the one it joins: the
// tributary meets the main stem where its own trace comes closest); then three rounds in which
// every end's gap is closed over the vertices next to it, as many as make the gap at most tan 8
// degrees of their length (at least `ramp`; weights (1 + cos(pi j / m)) / 2 over m vertices,
// j = 0 at the end: the line bends smoothly to its junction; all gaps of a round measured before
// any is closed, so the result does not depend on the order), then the end set to it exactly.
inline double plan_length(double x, double y) { return std::sqrt(x * x + y * y); }

// `line_of`: the line of each vertex (with window > 0).
void join_ends(DrapedLineSet& set, std::vector<std::uint32_t> follow, int ramp, int window,
               const std::vector<std::uint32_t>& line_of) {
    constexpr double tan_bend = 0.14054083470239145;  // tan 8 degrees
    std::vector<glm::vec2> gap(follow.size() / 3);
    for (std::size_t k = 0; k < gap.size() && window > 0; ++k) {
        const DrapedVertex& e = set.vertices[follow[3 * k + 1]];
        const std::uint32_t t = follow[3 * k + 2];
        const DrapedLine& into = set.lines[line_of[t]];
        // interior vertices only (an end's target stays an interior vertex)
        const std::uint32_t lo = std::max<std::int64_t>(std::int64_t(into.first) + 1, std::int64_t(t) - window);
        const std::uint32_t hi = std::min<std::int64_t>(std::int64_t(into.first) + into.count - 2, std::int64_t(t) + window);
        double best = 1e300;
        for (std::uint32_t j = lo; j <= hi; ++j) {
            const double d = plan_length(double(set.vertices[j].x) - e.x, double(set.vertices[j].y) - e.y);
            if (d < best) best = d, follow[3 * k + 2] = j;
        }
    }
    for (int round = 0; round < 3 && ramp > 1; ++round) {
        for (std::size_t k = 0; k < gap.size(); ++k) {
            const DrapedVertex &e = set.vertices[follow[3 * k + 1]], &t = set.vertices[follow[3 * k + 2]];
            gap[k] = {t.x - e.x, t.y - e.y};
        }
        for (std::size_t k = 0; k < gap.size(); ++k) {
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
                const float w = 0.5f * (1.0f + std::cos(3.14159265358979f * float(j) / float(m)));
                DrapedVertex& v = at(j);
                v.x += w * gap[k].x, v.y += w * gap[k].y;
            }
        }
    }
    for (std::size_t k = 0; k < follow.size(); k += 3) {
        set.vertices[follow[k + 1]].x = set.vertices[follow[k + 2]].x;
        set.vertices[follow[k + 1]].y = set.vertices[follow[k + 2]].y;
    }
}

}  // namespace

DrapedLineSet network_stems(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                            std::vector<std::uint32_t>* cells) {
    const StemWalk walk(g, dir, net);
    std::vector<std::uint32_t> sources;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (g.valid[i] && walk.indeg[i] == 0) sources.push_back(std::uint32_t(i));
    DrapedLineSet set;
    set.lines.resize(sources.size());
    parallel_chunks(sources.size(), 1024, [&](std::size_t s0, std::size_t s1) {  // sizes and orders first
        for (std::size_t s = s0; s < s1; ++s) {
            std::uint32_t n = 0;
            set.lines[s].order = walk.walk(sources[s], [&](const DvVertex&, std::size_t) { ++n; });
            set.lines[s].count = n;
        }
    });
    std::uint64_t next = 0;
    for (DrapedLine& l : set.lines) {
        if (next > 0xffffffffull - l.count)
            throw Error("drainage", "", "too many stem vertices for the database (4 G or more)", ExitCode::internal);
        l.first = std::uint32_t(next), next += l.count;
    }
    set.vertices.resize(next);
    if (cells) cells->resize(next);
    parallel_chunks(sources.size(), 1024, [&](std::size_t s0, std::size_t s1) {
        for (std::size_t s = s0; s < s1; ++s) {
            DrapedVertex* out = set.vertices.data() + set.lines[s].first;
            std::uint32_t* cell = cells ? cells->data() + set.lines[s].first : nullptr;
            walk.walk(sources[s], [&](const DvVertex& v, std::size_t c) {
                *out++ = draped(v);
                if (cell) *cell++ = std::uint32_t(c);
            });
        }
    });
    return set;
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

void smooth_lines(DrapedLineSet& set, double sigma) {
    const std::vector<std::uint32_t> follow = end_matches(set);
    glm::vec2 lo, hi;
    vertex_box(set, lo, hi);
    smooth_each_line(set, sigma);
    join_ends(set, follow, int(std::ceil(3.0 * sigma)), 0, {});
    clamp_to_box(set, lo, hi);
}

void smooth_stems(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                  const FallLineOptions& options) {
    const std::vector<std::uint32_t> follow = end_matches(set);
    glm::vec2 lo, hi;
    vertex_box(set, lo, hi);
    std::vector<std::uint8_t> joined(set.lines.size(), 0);  // lines whose last vertex is a junction
    for (std::size_t k = 0; k < follow.size(); k += 3)
        if (follow[k + 1] != set.lines[follow[k]].first) joined[follow[k]] = 1;
    trace_fall_lines(set, cells, g, options, joined);
    join_ends(set, follow, int(std::ceil(3.0 * options.sigma)), int(std::ceil(2.0 * options.corridor)), line_ids(set));
    clamp_to_box(set, lo, hi);
}

void drape_lines(DrapedLineSet& set, const DemSurface& surface, const LineProgress& progress) {
    // In batches of lines so the progress moves; each thread walks its lines with the cell of the
    // vertex before as the next one's start.
    constexpr std::size_t batches = 16;
    const std::size_t nl = set.lines.size(), per = (nl + batches - 1) / batches;
    for (std::size_t b = 0; b < batches && b * per < nl; ++b) {
        const std::size_t end = std::min(nl, (b + 1) * per);
        parallel_chunks(end - b * per, 256, [&](std::size_t l0, std::size_t l1) {
            const DemDraper draper(surface);
            for (std::size_t i = b * per + l0; i < b * per + l1; ++i) {
                const DrapedLine& l = set.lines[i];
                int c = -1, r = -1;
                for (std::uint32_t k = 0; k < l.count; ++k) {
                    DrapedVertex& v = set.vertices[l.first + k];
                    DemHit hit;
                    if (!draper.locate(v.x, v.y, c, r, hit)) {
                        v.nx = v.ny = v.nz = 0.0f;
                        continue;
                    }
                    glm::vec3 p, n;
                    draper.position_normal(hit, p, n);
                    v.z = p.z, v.nx = n.x, v.ny = n.y, v.nz = n.z;
                }
            }
        });
        if (progress) progress(double(end) / double(nl));
    }
    index_lines(set);
    if (progress) progress(1.0);
}

void smooth_and_drape(DrapedLineSet& set, const DemSurface& surface, const LineProgress& progress) {
    smooth_lines(set);
    drape_lines(set, surface, progress);
}

void build_draped_lines(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                        DrainageDb& db, const LineProgress& progress) {
    auto report = [&](double f) {
        if (progress) progress(f);
    };
    // smoothing (its table of line ends) before the surface's normals: never both in memory
    {
        std::vector<std::uint32_t> cells;
        db.creases = network_stems(g, dir, net, &cells);
        report(0.05);
        smooth_stems(db.creases, cells, g, fall_line_options(g));
    }
    report(0.1);
    db.ridges = listed_lines(db.divide_vertices, divide_polylines(db));
    smooth_lines(db.ridges, 3.0 * fall_line_options(g).sigma);
    report(0.15);
    const DemSurface surface(g);
    snap_to_crests(db.ridges, surface, crest_options(g));
    report(0.2);
    const double nc = double(db.creases.vertices.size()), nr = double(db.divide_vertices.size());
    const double share = nc + nr > 0.0 ? nc / (nc + nr) : 1.0;
    drape_lines(db.creases, surface, [&](double f) { report(0.2 + 0.8 * share * f); });
    drape_lines(db.ridges, surface, [&](double f) { report(0.2 + 0.8 * (share + (1.0 - share) * f)); });
}

}  // namespace penink
