#include "drainage/tiled_accumulation.hpp"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "core/error.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/band_passes.hpp"
#include "drainage/d8.hpp"
#include "drainage/flow_network.hpp"

namespace penink {

namespace {

[[noreturn]] void cycle() { throw Error("drainage", "", "flow directions contain a cycle", ExitCode::internal); }

// One band's directions and valid flags (its rows alone).
struct BandDirs {
    int cols = 0, r0 = 0, r1 = 0;
    std::vector<std::uint8_t> dir, valid;
    std::size_t size() const { return dir.size(); }
    // The cell of the band cell i points at, or -1 when it points out of the band (or is an outlet:
    // `out` tells which).
    std::int64_t target(std::size_t i, bool& out) const {
        out = false;
        if (!dir[i]) return -1;
        const int k = d8_index(dir[i]);
        const int c = int(i % std::size_t(cols)) + d8_dc[k], r = r0 + int(i / std::size_t(cols)) + d8_dr[k];
        if (r < r0 || r >= r1) {
            out = true;
            return -1;
        }
        if (c < 0 || c >= cols) cycle();  // off the grid's side: not a direction a valid grid has
        return std::int64_t(r - r0) * cols + c;
    }
};

BandDirs read_band(const FillBands& bands, int b, const DirRowReader& read) {
    if (b < 0 || b >= bands.count()) throw std::out_of_range("tiled accumulation: no such band");
    BandDirs d;
    d.cols = bands.cols, d.r0 = bands.first_row(b), d.r1 = bands.end_row(b);
    const std::size_t n = std::size_t(d.r1 - d.r0) * std::size_t(bands.cols);
    d.dir.resize(n), d.valid.resize(n);
    read(d.r0, d.r1, d.dir.data(), d.valid.data());
    return d;
}

// The band's accumulation counting its own cells upstream, each cell itself, and seed(i) more at
// cell i (an in-degree walk, as accumulate_flow's).
template <class Seed> std::vector<std::uint64_t> accumulate_band(const BandDirs& d, Seed&& seed) {
    const std::size_t n = d.size();
    std::vector<std::uint8_t> count(n, 0);
    std::vector<std::int64_t> next(n);
    for (std::size_t i = 0; i < n; ++i) {
        bool out;
        next[i] = d.valid[i] ? d.target(i, out) : -1;
        if (next[i] >= 0) ++count[std::size_t(next[i])];
    }
    std::vector<std::uint64_t> acc(n, 0);
    std::size_t done = 0, valid = 0;
    std::vector<std::uint8_t> walked(n, 0);
    for (std::size_t s = 0; s < n; ++s) {
        if (!d.valid[s]) continue;
        ++valid;
        if (count[s] != 0 || walked[s]) continue;
        for (std::size_t c = s;;) {
            acc[c] += 1 + seed(c);
            walked[c] = 1, ++done;
            if (next[c] < 0) break;
            const auto t = std::size_t(next[c]);
            acc[t] += acc[c];
            if (--count[t] != 0) break;
            c = t;
        }
    }
    if (done != valid) cycle();
    return acc;
}

// The perimeter rows of the band of rows [r0, r1): its first, then its last where it is another.
std::vector<int> edge_rows(int r0, int r1) { return r1 - 1 != r0 ? std::vector<int>{r0, r1 - 1} : std::vector<int>{r0}; }
std::vector<int> perimeter_rows_of(const BandDirs& d) { return edge_rows(d.r0, d.r1); }

// The perimeter node (of another band) that cell (c, r) of the band of rows [r0, r1) points at
// with code `dir` where the direction leaves the band; -1 where it stays in the band or dir is
// 0. A direction leaving towards no cell of the grid is refused (cycle).
std::int64_t leaving(const AccPerimeter& per, int c, int r, std::uint8_t dir, int r0, int r1) {
    if (!dir) return -1;
    const int d = d8_index(dir);
    const int tr = r + d8_dr[d], tc = c + d8_dc[d];
    if (tr >= r0 && tr < r1) return -1;
    const std::int64_t p = per.node(tc, tr);
    if (p < 0) cycle();
    return p;
}

}  // namespace

AccPerimeter::AccPerimeter(const FillBands& bands) : cols(bands.cols), row_index(std::size_t(bands.rows), -1) {
    for (int b = 0; b < bands.count(); ++b)
        for (const int r : {bands.first_row(b), bands.end_row(b) - 1})
            if (row_index[std::size_t(r)] < 0) row_index[std::size_t(r)] = 0, rows.push_back(r);
    std::sort(rows.begin(), rows.end());
    for (std::size_t k = 0; k < rows.size(); ++k) row_index[std::size_t(rows[k])] = int(k);
}

std::int64_t AccPerimeter::node(int c, int r) const {
    if (r < 0 || r >= int(row_index.size()) || c < 0 || c >= cols || row_index[std::size_t(r)] < 0) return -1;
    return std::int64_t(row_index[std::size_t(r)]) * cols + c;
}

AccSurvey survey_accumulation_band(const FillBands& bands, int b, const DirRowReader& read) {
    const BandDirs d = read_band(bands, b, read);
    const std::vector<std::uint64_t> acc = accumulate_band(d, [](std::size_t) { return std::uint64_t(0); });
    const AccPerimeter per(bands);
    const std::size_t n = d.size(), cols = std::size_t(d.cols);
    // each perimeter cell's link: the last cell of its path in the band where the path leaves it
    constexpr std::int64_t unknown = -2, none = -1;
    std::vector<std::int64_t> exit(n, unknown);
    std::vector<std::size_t> path;
    AccSurvey s;
    s.band = b;
    // each outlet's rank among the band's, row-major
    std::vector<std::int64_t> rank(n, -1);
    for (std::size_t i = 0; i < n; ++i)
        if (d.valid[i] && !d.dir[i]) rank[i] = std::int64_t(s.outlets++);
    std::vector<std::int64_t> end(n, unknown);  // the outlet rank each path ends at, -1 leaving
    for (const int r : perimeter_rows_of(d))
        for (std::size_t c = 0; c < cols; ++c) {
            const std::size_t p = std::size_t(r - d.r0) * cols + c;
            s.acc.push_back(std::uint32_t(acc[p])), s.dir.push_back(d.dir[p]), s.valid.push_back(d.valid[p]);
            if (!d.valid[p]) {
                s.link.push_back(none), s.outlet.push_back(none);
                continue;
            }
            path.clear();
            std::size_t at = p;
            std::int64_t found = none, ends = none;
            for (std::size_t steps = 0;; ++steps) {
                if (exit[at] != unknown) {  // a path walked before: its end
                    found = exit[at], ends = end[at];
                    break;
                }
                if (steps > n) cycle();
                path.push_back(at);
                bool out;
                const std::int64_t t = d.target(at, out);
                if (out) {  // leaves the band here
                    found = per.node(int(at % cols), d.r0 + int(at / cols));
                    break;
                }
                if (t < 0) {  // an outlet of the band
                    ends = rank[at];
                    break;
                }
                at = std::size_t(t);
            }
            for (const std::size_t q : path) exit[q] = found, end[q] = ends;
            s.link.push_back(found), s.outlet.push_back(ends);
        }
    return s;
}

std::vector<std::uint64_t> accumulation_inflows(const FillBands& bands, const std::vector<AccSurvey>& surveys) {
    const AccPerimeter per(bands);
    const std::size_t nodes = per.nodes(), cols = std::size_t(bands.cols);
    std::vector<std::uint64_t> local(nodes, 0), total(nodes, 0), inflow(nodes, 0);
    std::vector<std::int64_t> link(nodes, -1), out(nodes, -1);
    std::vector<std::uint8_t> seen(std::size_t(bands.count()), 0), valid(nodes, 0);
    for (const AccSurvey& s : surveys) {
        if (s.band < 0 || s.band >= bands.count() || seen[std::size_t(s.band)])
            throw std::invalid_argument("tiled accumulation: surveys must cover each band once");
        seen[std::size_t(s.band)] = 1;
        const int r0 = bands.first_row(s.band), r1 = bands.end_row(s.band);
        const std::vector<int> rows = edge_rows(r0, r1);
        if (s.acc.size() != rows.size() * cols || s.dir.size() != s.acc.size() || s.valid.size() != s.acc.size() ||
            s.link.size() != s.acc.size() || s.outlet.size() != s.acc.size())
            throw std::invalid_argument("tiled accumulation: a survey of another grid");
        for (std::size_t k = 0; k < s.acc.size(); ++k) {
            const int r = rows[k / cols], c = int(k % cols);
            const auto p = std::size_t(per.node(c, r));
            local[p] = s.acc[k], link[p] = s.link[k], valid[p] = s.valid[k];
            if (link[p] >= std::int64_t(nodes)) throw std::invalid_argument("tiled accumulation: a survey of another grid");
            if (s.valid[k]) out[p] = leaving(per, c, r, s.dir[k], r0, r1);
        }
    }
    if (std::find(seen.begin(), seen.end(), 0) != seen.end())
        throw std::invalid_argument("tiled accumulation: a band's survey is missing");
    // a node's total waits for the inflow of every node linked to it, a node's inflow for the
    // total of every node of another band pointing at it
    std::vector<std::uint32_t> wait_total(nodes, 0), wait_inflow(nodes, 0);
    for (std::size_t p = 0; p < nodes; ++p) {
        if (!valid[p]) continue;
        if (link[p] >= 0) ++wait_total[std::size_t(link[p])];
        if (out[p] >= 0) ++wait_inflow[std::size_t(out[p])];
    }
    std::vector<std::size_t> ready;  // nodes whose inflow is known
    for (std::size_t p = 0; p < nodes; ++p)
        if (valid[p] && wait_inflow[p] == 0) ready.push_back(p);
    std::size_t done = 0, count = std::size_t(std::count(valid.begin(), valid.end(), 1));
    while (!ready.empty()) {
        const std::size_t q = ready.back();
        ready.pop_back();
        ++done;
        if (link[q] < 0) continue;  // its inflow ends at an outlet in its band
        const auto e = std::size_t(link[q]);
        total[e] += inflow[q];
        if (--wait_total[e] != 0) continue;
        total[e] += local[e];  // every inflow linked to it known: its total
        if (out[e] < 0) continue;
        const auto t = std::size_t(out[e]);
        inflow[t] += total[e];
        if (--wait_inflow[t] == 0) ready.push_back(t);
    }
    if (done != count) cycle();
    return inflow;
}

void finish_accumulation_band(const FillBands& bands, int b, const DirRowReader& read,
                              const std::vector<std::uint64_t>& inflow, std::vector<std::uint32_t>& acc) {
    const AccPerimeter per(bands);
    if (inflow.size() != per.nodes()) throw std::invalid_argument("tiled accumulation: inflows of another grid");
    const BandDirs d = read_band(bands, b, read);
    const std::size_t cols = std::size_t(d.cols);
    const std::vector<std::uint64_t> a = accumulate_band(d, [&](std::size_t i) {
        const std::int64_t p = per.node(int(i % cols), d.r0 + int(i / cols));
        return p < 0 ? std::uint64_t(0) : inflow[std::size_t(p)];
    });
    acc.resize(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) acc[i] = std::uint32_t(a[i]);
}

PerimeterBasins perimeter_basins(const FillBands& bands, const std::vector<AccSurvey>& surveys) {
    const AccPerimeter per(bands);
    const std::size_t nodes = per.nodes(), cols = std::size_t(bands.cols);
    const int n = bands.count();
    PerimeterBasins out;
    out.first_outlet.assign(std::size_t(n), 0);
    out.label.assign(nodes, 0);
    std::vector<const AccSurvey*> by_band(std::size_t(n), nullptr);
    for (const AccSurvey& s : surveys) {
        if (s.band < 0 || s.band >= n || by_band[std::size_t(s.band)] || s.link.size() != s.valid.size() ||
            s.outlet.size() != s.valid.size() || s.dir.size() != s.valid.size())
            throw std::invalid_argument("tiled basins: surveys must cover each band once");
        by_band[std::size_t(s.band)] = &s;
    }
    std::uint64_t above = 0;
    for (int b = 0; b < n; ++b) {
        if (!by_band[std::size_t(b)]) throw std::invalid_argument("tiled basins: a band's survey is missing");
        out.first_outlet[std::size_t(b)] = above, above += by_band[std::size_t(b)]->outlets;
    }
    // each node: its label where its path ends at an outlet of its band, else the node of another
    // band its exit points at
    std::vector<std::int64_t> then(nodes, -1);
    std::vector<std::uint8_t> valid(nodes, 0);
    for (const AccSurvey* s : by_band) {
        const int r0 = bands.first_row(s->band), r1 = bands.end_row(s->band);
        const std::vector<int> rows = edge_rows(r0, r1);
        if (s->valid.size() != rows.size() * cols) throw std::invalid_argument("tiled basins: a survey of another grid");
        for (std::size_t k = 0; k < s->valid.size(); ++k) {
            if (!s->valid[k]) continue;
            const auto p = std::size_t(per.node(int(k % cols), rows[k / cols]));
            valid[p] = 1;
            if (s->outlet[k] >= 0) {
                out.label[p] = std::uint32_t(1 + out.first_outlet[std::size_t(s->band)] + std::uint64_t(s->outlet[k]));
                continue;
            }
            if (s->link[k] < 0 || s->link[k] >= std::int64_t(nodes)) cycle();
            const auto e = std::size_t(s->link[k]);  // its exit: a perimeter cell of this band
            const int er = per.rows[e / cols], ec = int(e % cols);
            // the exit's own direction, from its survey row
            const std::size_t ek = std::size_t(er == r0 ? 0 : 1) * cols + std::size_t(ec);
            if (ek >= s->dir.size()) cycle();
            then[p] = leaving(per, ec, er, s->dir[ek], r0, r1);
            if (then[p] < 0) cycle();  // an exit that does not leave: not a survey of these directions
        }
    }
    std::vector<std::size_t> path;
    for (std::size_t p = 0; p < nodes; ++p) {
        if (!valid[p] || out.label[p]) continue;
        path.clear();
        std::size_t at = p;
        while (!out.label[at]) {
            if (path.size() > nodes || then[at] < 0) cycle();
            path.push_back(at);
            at = std::size_t(then[at]);
        }
        for (const std::size_t q : path) out.label[q] = out.label[at];
    }
    return out;
}

void finish_basin_band(const FillBands& bands, int b, const DirRowReader& read, const PerimeterBasins& basins,
                       std::vector<std::uint32_t>& labels) {
    const AccPerimeter per(bands);
    if (basins.label.size() != per.nodes() || basins.first_outlet.size() != std::size_t(bands.count()))
        throw std::invalid_argument("tiled basins: labels of another grid");
    const BandDirs d = read_band(bands, b, read);
    const std::size_t n = d.size(), cols = std::size_t(d.cols);
    labels.assign(n, 0);
    std::uint64_t outlets = basins.first_outlet[std::size_t(b)];
    for (std::size_t i = 0; i < n; ++i)
        if (d.valid[i] && !d.dir[i]) labels[i] = std::uint32_t(++outlets);
    std::vector<std::size_t> path;
    for (std::size_t i = 0; i < n; ++i) {
        if (!d.valid[i] || labels[i]) continue;
        path.clear();
        std::size_t at = i;
        while (!labels[at]) {
            if (path.size() > n) cycle();
            path.push_back(at);
            bool out;
            const std::int64_t t = d.target(at, out);
            if (out) {  // a perimeter cell whose path leaves the band: its label from the solve
                const std::int64_t p = per.node(int(at % cols), d.r0 + int(at / cols));
                if (p < 0 || !basins.label[std::size_t(p)]) cycle();
                labels[at] = basins.label[std::size_t(p)];
                break;
            }
            if (t < 0) cycle();  // not an outlet (labelled above), not leaving: cannot be
            at = std::size_t(t);
        }
        for (const std::size_t q : path) labels[q] = labels[at];
    }
}

namespace {

// x folded into a pending byte (push_order) as many times as pending byte p holds its maximum:
// p's cells pushed one by one give the same byte.
void push_pending(std::uint8_t& into, std::uint8_t p) {
    if (!p) return;
    push_order(into, std::uint8_t(p >> 1));
    if (p & 1) push_order(into, std::uint8_t(p >> 1));
}

// The order of a cell of local fold `pending` whose one other upstream cell has order x.
std::uint8_t order_with(std::uint8_t pending, std::uint8_t x) {
    push_order(pending, x);
    return final_order(pending);
}

// Orders of the band's cells by an in-degree walk, each cell's fold starting from start[i]; the
// walk goes on only through cells `through` allows (the others keep their fold in `pending`).
template <class Through>
void order_walk(const BandDirs& d, const std::vector<std::int64_t>& next, std::vector<std::uint8_t>& pending,
                std::vector<std::uint8_t>& order, Through&& through) {
    const std::size_t n = d.size();
    std::vector<std::uint8_t> count(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        if (d.valid[i] && through(i) && next[i] >= 0) ++count[std::size_t(next[i])];
    order.assign(n, 0);
    for (std::size_t s = 0; s < n; ++s) {
        if (!d.valid[s] || !through(s) || count[s] != 0 || order[s]) continue;
        for (std::size_t c = s;;) {
            order[c] = final_order(pending[c]);
            if (next[c] < 0) break;
            const auto t = std::size_t(next[c]);
            push_order(pending[t], order[c]);
            if (!through(t) || --count[t] != 0) break;
            c = t;
        }
    }
}

std::vector<std::int64_t> next_cells(const BandDirs& d) {
    std::vector<std::int64_t> next(d.size(), -1);
    for (std::size_t i = 0; i < d.size(); ++i) {
        bool out;
        if (d.valid[i]) next[i] = d.target(i, out);
    }
    return next;
}

}  // namespace

OrderSurvey survey_order_band(const FillBands& bands, int b, const DirRowReader& read) {
    const BandDirs d = read_band(bands, b, read);
    const std::size_t n = d.size(), cols = std::size_t(d.cols);
    const std::vector<std::int64_t> next = next_cells(d);
    // cells downstream of an edge cell (in the band)
    std::vector<std::uint8_t> reached(n, 0), edge(n, 0);
    for (const int r : perimeter_rows_of(d))
        for (std::size_t c = 0; c < cols; ++c) {
            const std::size_t p = std::size_t(r - d.r0) * cols + c;
            if (!d.valid[p]) continue;
            edge[p] = 1;
            for (std::size_t at = p, steps = 0; !reached[at]; ++steps) {
                if (steps > n) cycle();
                reached[at] = 1;
                if (next[at] < 0) break;
                at = std::size_t(next[at]);
            }
        }
    // the others' orders are final; a reached cell keeps the fold of its other upstream cells
    std::vector<std::uint8_t> pending(n, 0), order;
    order_walk(d, next, pending, order, [&](std::size_t i) { return !reached[i]; });
    std::vector<std::uint8_t> from_reached(n, 0);  // reached upstream cells of each cell
    for (std::size_t i = 0; i < n; ++i)
        if (reached[i] && next[i] >= 0) ++from_reached[std::size_t(next[i])];
    OrderSurvey s;
    s.band = b;
    std::vector<std::int32_t> node_of(n, -1);
    for (std::size_t i = 0; i < n; ++i)
        if (d.valid[i] && reached[i] && (edge[i] || from_reached[i] >= 2)) {
            node_of[i] = std::int32_t(s.cell.size());
            s.cell.push_back(std::int64_t(i)), s.pending.push_back(pending[i]), s.dir.push_back(d.dir[i]);
        }
    s.down.assign(s.cell.size(), -1);
    s.table_at.push_back(0);
    for (std::size_t k = 0; k < s.cell.size(); ++k) {
        // the order reaching the next node for this node's order x: the cells between apply
        // order_with in turn; above every fold's maximum x passes unchanged
        std::vector<std::size_t> between;
        std::int64_t at = next[std::size_t(s.cell[k])];
        for (; at >= 0 && node_of[std::size_t(at)] < 0; at = next[std::size_t(at)]) {
            if (between.size() > n) cycle();
            between.push_back(std::size_t(at));
        }
        if (at >= 0) {
            s.down[k] = node_of[std::size_t(at)];
            int top = 0;
            for (const std::size_t c : between) top = std::max(top, pending[c] >> 1);
            for (int x = 0; x <= top + 1; ++x) {
                std::uint8_t o = std::uint8_t(x);
                for (const std::size_t c : between) o = order_with(pending[c], o);
                s.tables.push_back(o);
            }
        }
        s.table_at.push_back(std::uint32_t(s.tables.size()));
    }
    return s;
}

std::vector<std::uint8_t> perimeter_order_inflows(const FillBands& bands, const std::vector<OrderSurvey>& surveys) {
    const AccPerimeter per(bands);
    const std::size_t cols = std::size_t(bands.cols), pnodes = per.nodes();
    const int nb = bands.count();
    std::vector<const OrderSurvey*> by_band(std::size_t(nb), nullptr);
    for (const OrderSurvey& s : surveys) {
        if (s.band < 0 || s.band >= nb || by_band[std::size_t(s.band)] || s.pending.size() != s.cell.size() ||
            s.dir.size() != s.cell.size() || s.down.size() != s.cell.size() || s.table_at.size() != s.cell.size() + 1 ||
            s.table_at.back() != s.tables.size())
            throw std::invalid_argument("tiled order: surveys must cover each band once");
        by_band[std::size_t(s.band)] = &s;
    }
    // every band's nodes numbered one after the other
    std::vector<std::size_t> first(std::size_t(nb) + 1, 0);
    for (int b = 0; b < nb; ++b) {
        if (!by_band[std::size_t(b)]) throw std::invalid_argument("tiled order: a band's survey is missing");
        first[std::size_t(b) + 1] = first[std::size_t(b)] + by_band[std::size_t(b)]->cell.size();
    }
    const std::size_t total = first.back();
    std::vector<std::int64_t> perimeter(total, -1);  // a node's perimeter node, -1 for a meeting of paths
    std::vector<std::int64_t> of_perimeter(pnodes, -1);
    std::vector<std::int64_t> out(total, -1);        // the node of another band it points at
    for (int b = 0; b < nb; ++b) {
        const OrderSurvey& s = *by_band[std::size_t(b)];
        const int r0 = bands.first_row(b), r1 = bands.end_row(b);
        for (std::size_t k = 0; k < s.cell.size(); ++k) {
            const std::size_t v = first[std::size_t(b)] + k;
            if (s.cell[k] < 0 || s.cell[k] >= std::int64_t(std::size_t(r1 - r0) * cols) ||
                s.down[k] >= std::int32_t(s.cell.size()))
                throw std::invalid_argument("tiled order: a survey of another grid");
            const int r = r0 + int(std::size_t(s.cell[k]) / cols), c = int(std::size_t(s.cell[k]) % cols);
            perimeter[v] = per.node(c, r);
            if (perimeter[v] >= 0) of_perimeter[std::size_t(perimeter[v])] = std::int64_t(v);
        }
    }
    for (int b = 0; b < nb; ++b) {
        const OrderSurvey& s = *by_band[std::size_t(b)];
        const int r0 = bands.first_row(b), r1 = bands.end_row(b);
        for (std::size_t k = 0; k < s.cell.size(); ++k) {
            const std::int64_t p = leaving(per, int(std::size_t(s.cell[k]) % cols), r0 + int(std::size_t(s.cell[k]) / cols),
                                           s.dir[k], r0, r1);
            if (p < 0) continue;
            if (of_perimeter[std::size_t(p)] < 0) cycle();
            out[first[std::size_t(b)] + k] = of_perimeter[std::size_t(p)];
        }
    }
    // in flow order: a node's order once every node upstream of it has given its share
    std::vector<std::uint8_t> fold(total, 0), ext(total, 0), order(total, 0);
    std::vector<std::uint32_t> wait(total, 0);
    std::vector<int> band_of(total);
    for (int b = 0; b < nb; ++b)
        for (std::size_t v = first[std::size_t(b)]; v < first[std::size_t(b) + 1]; ++v) {
            band_of[v] = b;
            const OrderSurvey& s = *by_band[std::size_t(b)];
            const std::size_t k = v - first[std::size_t(b)];
            fold[v] = s.pending[k];
            if (s.down[k] >= 0) ++wait[first[std::size_t(b)] + std::size_t(s.down[k])];
            if (out[v] >= 0) ++wait[std::size_t(out[v])];
        }
    std::vector<std::size_t> ready;
    for (std::size_t v = 0; v < total; ++v)
        if (!wait[v]) ready.push_back(v);
    std::size_t done = 0;
    while (!ready.empty()) {
        const std::size_t v = ready.back();
        ready.pop_back();
        ++done;
        order[v] = final_order(fold[v]);
        const int b = band_of[v];
        const OrderSurvey& s = *by_band[std::size_t(b)];
        const std::size_t k = v - first[std::size_t(b)];
        std::size_t to = total;
        if (s.down[k] >= 0) {
            to = first[std::size_t(b)] + std::size_t(s.down[k]);
            const std::uint32_t t0 = s.table_at[k], t1 = s.table_at[k + 1];
            push_order(fold[to], order[v] < t1 - t0 ? s.tables[t0 + order[v]] : order[v]);
        } else if (out[v] >= 0) {
            to = std::size_t(out[v]);
            push_order(fold[to], order[v]), push_order(ext[to], order[v]);
        }
        if (to < total && --wait[to] == 0) ready.push_back(to);
    }
    if (done != total) cycle();
    std::vector<std::uint8_t> inflow(pnodes, 0);
    for (std::size_t v = 0; v < total; ++v)
        if (perimeter[v] >= 0) inflow[std::size_t(perimeter[v])] = ext[v];
    return inflow;
}

void finish_order_band(const FillBands& bands, int b, const DirRowReader& read, const std::vector<std::uint8_t>& inflow,
                       std::vector<std::uint8_t>& order) {
    const AccPerimeter per(bands);
    if (inflow.size() != per.nodes()) throw std::invalid_argument("tiled order: inflows of another grid");
    const BandDirs d = read_band(bands, b, read);
    const std::size_t cols = std::size_t(d.cols);
    std::vector<std::uint8_t> pending(d.size(), 0);
    for (const int r : perimeter_rows_of(d))
        for (std::size_t c = 0; c < cols; ++c) {
            const std::size_t i = std::size_t(r - d.r0) * cols + c;
            push_pending(pending[i], inflow[std::size_t(per.node(int(c), r))]);
        }
    order_walk(d, next_cells(d), pending, order, [](std::size_t) { return true; });
    for (std::size_t i = 0; i < d.size(); ++i)
        if (d.valid[i] && !order[i]) cycle();
}

namespace {

std::vector<std::uint8_t> encode_acc_survey(const AccSurvey& s) {
    bands::Writer w;
    w.put(std::int32_t(s.band)), w.put(s.outlets), w.put_all(s.acc), w.put_all(s.dir), w.put_all(s.valid);
    w.put_all(s.link), w.put_all(s.outlet);
    return std::move(w.out);
}

AccSurvey decode_acc_survey(std::span<const std::uint8_t> bytes) {
    bands::Reader r{bytes};
    AccSurvey s;
    s.band = r.get<std::int32_t>();
    s.outlets = r.get<std::uint64_t>();
    s.acc = r.get_all<std::uint32_t>();
    s.dir = r.get_all<std::uint8_t>(s.acc.size()), s.valid = r.get_all<std::uint8_t>(s.acc.size());
    s.link = r.get_all<std::int64_t>(s.acc.size()), s.outlet = r.get_all<std::int64_t>(s.acc.size());
    r.end();
    return s;  // its size and links checked against the grid by accumulation_inflows
}

struct FinishedAcc {
    int band = 0;
    std::vector<std::uint32_t> acc;
};

template <class Survey, class SurveyFn>
std::vector<Survey> survey_list(const std::vector<int>& which, const DirRowReader& read, int threads, SurveyFn&& survey) {
    return bands::survey_list<Survey>(which, read, threads, survey, [] {});
}

template <class FinishFn>
void finish_list(const std::vector<int>& which, const DirRowReader& read, int threads, FinishFn&& finish,
                 const std::function<void(const FinishedAcc&)>& use) {
    bands::finish_in_order<FinishedAcc>(
        which, read, threads, [&](int b, const DirRowReader& r, FinishedAcc& out) { finish(b, r, out.acc); }, use);
}

// A pass over every band on this process: surveys, solve(surveys), finishes written in row order.
template <class Survey, class SurveyFn, class SolveFn, class FinishFn>
void banded_pass(const char* what, const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads,
                 SurveyFn&& survey, SolveFn&& solve, FinishFn&& finish) {
    if (bands.cols < 1 || bands.rows < 1 || bands.band_rows < 1) throw std::invalid_argument(std::string(what) + ": empty grid");
    if (threads <= 0) threads = rank_threads(nullptr);
    std::vector<int> all(static_cast<std::size_t>(bands.count()));
    for (int b = 0; b < bands.count(); ++b) all[std::size_t(b)] = b;
    const auto solved = solve(survey_list<Survey>(all, read, threads, survey));
    finish_list(
        all, read, threads, [&](int b, const DirRowReader& r, std::vector<std::uint32_t>& out) { finish(b, r, solved, out); },
        [&](const FinishedAcc& f) { write(bands.first_row(f.band), bands.end_row(f.band), f.acc.data()); });
}

}  // namespace

void tiled_accumulation(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads) {
    banded_pass<AccSurvey>(
        "tiled accumulation", bands, read, write, threads,
        [&](int b, const DirRowReader& r) { return survey_accumulation_band(bands, b, r); },
        [&](const std::vector<AccSurvey>& s) { return accumulation_inflows(bands, s); },
        [&](int b, const DirRowReader& r, const std::vector<std::uint64_t>& inflow, std::vector<std::uint32_t>& out) {
            finish_accumulation_band(bands, b, r, inflow, out);
        });
}

void tiled_basins(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads) {
    banded_pass<AccSurvey>(
        "tiled basins", bands, read, write, threads,
        [&](int b, const DirRowReader& r) { return survey_accumulation_band(bands, b, r); },
        [&](const std::vector<AccSurvey>& s) { return perimeter_basins(bands, s); },
        [&](int b, const DirRowReader& r, const PerimeterBasins& basins, std::vector<std::uint32_t>& out) {
            finish_basin_band(bands, b, r, basins, out);
        });
}

void tiled_strahler(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, int threads) {
    banded_pass<OrderSurvey>(
        "tiled order", bands, read, write, threads,
        [&](int b, const DirRowReader& r) { return survey_order_band(bands, b, r); },
        [&](const std::vector<OrderSurvey>& s) { return perimeter_order_inflows(bands, s); },
        [&](int b, const DirRowReader& r, const std::vector<std::uint8_t>& inflow, std::vector<std::uint32_t>& out) {
            std::vector<std::uint8_t> order;
            finish_order_band(bands, b, r, inflow, order);
            out.assign(order.begin(), order.end());
        });
}

namespace {

std::vector<std::uint8_t> encode_order_survey(const OrderSurvey& s) {
    bands::Writer w;
    w.put(std::int32_t(s.band)), w.put_all(s.cell), w.put_all(s.pending), w.put_all(s.dir), w.put_all(s.down);
    w.put_all(s.table_at), w.put_all(s.tables);
    return std::move(w.out);
}

OrderSurvey decode_order_survey(std::span<const std::uint8_t> bytes) {
    bands::Reader r{bytes};
    OrderSurvey s;
    s.band = r.get<std::int32_t>();
    s.cell = r.get_all<std::int64_t>();
    s.pending = r.get_all<std::uint8_t>(s.cell.size()), s.dir = r.get_all<std::uint8_t>(s.cell.size());
    s.down = r.get_all<std::int32_t>(s.cell.size()), s.table_at = r.get_all<std::uint32_t>(s.cell.size() + 1);
    s.tables = r.get_all<std::uint8_t>();
    r.end();
    return s;  // checked against the grid by perimeter_order_inflows
}

template <class T> std::vector<std::uint8_t> vector_bytes(const std::vector<T>& v) {
    bands::Writer w;
    w.put_all(v);
    return std::move(w.out);
}
template <class T> std::vector<T> bytes_vector(std::span<const std::uint8_t> bytes, std::size_t n) {
    bands::Reader r{bytes};
    std::vector<T> v = r.get_all<T>(n);
    r.end();
    return v;
}

// A pass over the bands spread over the ranks of a distributed run (bands::over_ranks): band b
// surveyed and finished by rank b % size; rank 0 solves the surveys and broadcasts what it solved
// (encode_solved, decode_solved on every rank), and writes the finished bands in row order.
template <class Survey, class SurveyFn, class EncodeSurvey, class DecodeSurvey, class SolveFn, class EncodeSolved,
          class DecodeSolved, class FinishFn>
void distributed_pass(const char* what, const FillBands& bands, const DirRowReader& read, const AccRowWriter& write,
                      Ranks& ranks, int threads, SurveyFn&& survey, EncodeSurvey&& encode_survey,
                      DecodeSurvey&& decode_survey, SolveFn&& solve, EncodeSolved&& encode_solved,
                      DecodeSolved&& decode_solved, FinishFn&& finish) {
    if (bands.cols < 1 || bands.rows < 1 || bands.band_rows < 1) throw std::invalid_argument(std::string(what) + ": empty grid");
    bands::over_ranks<Survey>(
        ranks, bands.count(), [&](const std::vector<int>& mine) { return survey_list<Survey>(mine, read, threads, survey); },
        encode_survey, decode_survey, [&](const std::vector<Survey>& s) { return encode_solved(solve(s)); },
        [&](const std::vector<int>& mine, std::vector<std::uint8_t> bytes, const auto& use) {
            const auto solved = decode_solved(bytes);
            bytes = {};
            finish_list(
                mine, read, threads, [&](int b, const DirRowReader& r, std::vector<std::uint32_t>& out) { finish(b, r, solved, out); },
                use);
        },
        [](const FinishedAcc& f) {
            bands::Writer w;
            w.put(std::int32_t(f.band)), w.put_all(f.acc);
            return std::move(w.out);
        },
        [&](int band, std::span<const std::uint8_t> m) {
            bands::Reader r{m};
            FinishedAcc f;
            f.band = r.get<std::int32_t>();
            if (f.band != band) throw std::runtime_error(std::string(what) + ": a band out of order");
            f.acc = r.get_all<std::uint32_t>(std::size_t(bands.end_row(band) - bands.first_row(band)) * std::size_t(bands.cols));
            r.end();
            return f;
        },
        [&](const FinishedAcc& f) { write(bands.first_row(f.band), bands.end_row(f.band), f.acc.data()); });
}

}  // namespace

void distributed_accumulation(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, Ranks& ranks,
                              int threads) {
    const std::size_t nodes = AccPerimeter(bands).nodes();
    distributed_pass<AccSurvey>(
        "tiled accumulation", bands, read, write, ranks, threads,
        [&](int b, const DirRowReader& r) { return survey_accumulation_band(bands, b, r); }, encode_acc_survey,
        decode_acc_survey, [&](const std::vector<AccSurvey>& s) { return accumulation_inflows(bands, s); },
        vector_bytes<std::uint64_t>, [&](std::span<const std::uint8_t> m) { return bytes_vector<std::uint64_t>(m, nodes); },
        [&](int b, const DirRowReader& r, const std::vector<std::uint64_t>& inflow, std::vector<std::uint32_t>& out) {
            finish_accumulation_band(bands, b, r, inflow, out);
        });
}

void distributed_basins(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, Ranks& ranks,
                        int threads) {
    const std::size_t nodes = AccPerimeter(bands).nodes();
    distributed_pass<AccSurvey>(
        "tiled basins", bands, read, write, ranks, threads,
        [&](int b, const DirRowReader& r) { return survey_accumulation_band(bands, b, r); }, encode_acc_survey,
        decode_acc_survey, [&](const std::vector<AccSurvey>& s) { return perimeter_basins(bands, s); },
        [](const PerimeterBasins& p) {
            bands::Writer w;
            w.put_all(p.first_outlet), w.put_all(p.label);
            return std::move(w.out);
        },
        [&](std::span<const std::uint8_t> m) {
            bands::Reader r{m};
            PerimeterBasins p;
            p.first_outlet = r.get_all<std::uint64_t>(std::size_t(bands.count()));
            p.label = r.get_all<std::uint32_t>(nodes);
            r.end();
            return p;
        },
        [&](int b, const DirRowReader& r, const PerimeterBasins& basins, std::vector<std::uint32_t>& out) {
            finish_basin_band(bands, b, r, basins, out);
        });
}

void distributed_strahler(const FillBands& bands, const DirRowReader& read, const AccRowWriter& write, Ranks& ranks,
                          int threads) {
    const std::size_t nodes = AccPerimeter(bands).nodes();
    distributed_pass<OrderSurvey>(
        "tiled order", bands, read, write, ranks, threads,
        [&](int b, const DirRowReader& r) { return survey_order_band(bands, b, r); }, encode_order_survey,
        decode_order_survey, [&](const std::vector<OrderSurvey>& s) { return perimeter_order_inflows(bands, s); },
        vector_bytes<std::uint8_t>, [&](std::span<const std::uint8_t> m) { return bytes_vector<std::uint8_t>(m, nodes); },
        [&](int b, const DirRowReader& r, const std::vector<std::uint8_t>& inflow, std::vector<std::uint32_t>& out) {
            std::vector<std::uint8_t> order;
            finish_order_band(bands, b, r, inflow, order);
            out.assign(order.begin(), order.end());
        });
}

}  // namespace penink
