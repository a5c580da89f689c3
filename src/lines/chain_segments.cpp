#include "lines/chain_segments.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "lines/simplify.hpp"

namespace penink {

namespace {

struct Node {
    glm::vec2 sum{0.0f};
    float depth_sum = 0.0f;
    int count = 0;
    glm::vec2 leader{0.0f};
    std::vector<int> ends;  // end ids 2*piece (+1 for the last point) in input order
    int through[2] = {-1, -1};  // the two ends a chain continues through; -1: it ends at every end
    bool passes(int e) const { return e == through[0] || e == through[1]; }
    int other(int e) const { return e == through[0] ? through[1] : through[0]; }
};

std::uint64_t cell_key(int cx, int cy) {
    return (std::uint64_t(std::uint32_t(cx)) << 32) | std::uint32_t(cy);
}

// Greedy leader clustering of end points: each joins the nearest node leader within tol.
std::vector<int> cluster_ends(const std::vector<glm::vec2>& ends, float tol, std::vector<Node>& nodes) {
    const float cell = std::max(tol, 1e-3f);
    std::unordered_map<std::uint64_t, std::vector<int>> grid;
    std::vector<int> node_of(ends.size());
    for (std::size_t e = 0; e < ends.size(); ++e) {
        int cx = int(std::floor(ends[e].x / cell)), cy = int(std::floor(ends[e].y / cell));
        int best = -1;
        float best_d = 0.0f;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                auto it = grid.find(cell_key(cx + dx, cy + dy));
                if (it == grid.end()) continue;
                for (int n : it->second) {
                    float d = glm::length(nodes[n].leader - ends[e]);
                    if (d <= tol && (best < 0 || d < best_d || (d == best_d && n < best)))
                        best = n, best_d = d;
                }
            }
        if (best < 0) {
            best = int(nodes.size());
            nodes.push_back({});
            nodes.back().leader = ends[e];
            grid[cell_key(cx, cy)].push_back(best);
        }
        node_of[e] = best;
    }
    return node_of;
}

struct Graph {
    std::vector<Stroke>* pieces = nullptr;
    std::vector<Node> nodes;
    std::vector<int> node_of;  // per end id
    std::vector<char> used;    // per piece
    bool weighted = false;     // some piece carries weights: the chains carry them (1 where none)
};

glm::vec2 leaving_dir(const Stroke& s, bool from_start) {
    glm::vec2 a = from_start ? s.points.front() : s.points.back();
    glm::vec2 b = from_start ? s.points[1] : s.points[s.points.size() - 2];
    glm::vec2 d = b - a;
    float l = glm::length(d);
    return l > 0.0f ? d / l : d;
}

// Depth of a piece near end e: the median of its first five points from that end (the end point
// itself left out when the piece has more), 0 when unknown.
float end_depth(const Stroke& s, int e) {
    const std::size_t n = s.points.size();
    std::vector<float> d;
    for (std::size_t k = n > 2 ? 1 : 0; k < n && d.size() < 5; ++k) d.push_back(s.depth[e % 2 == 0 ? k : n - 1 - k]);
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
    return d.empty() ? 0.0f : d[d.size() / 2];
}

// Nodes of two ends that lie within tol of a third piece's points (T-junctions left by an
// earlier pass: that piece passes through the node).
std::vector<char> t_nodes(const Graph& g, float tol) {
    const float cell = std::max(tol, 1e-3f);
    std::unordered_map<std::uint64_t, std::vector<int>> grid;  // piece ids by cell of their points
    const auto& ps = *g.pieces;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (g.used[i]) continue;
        for (const glm::vec2& p : ps[i].points) {
            std::vector<int>& c = grid[cell_key(int(std::floor(p.x / cell)), int(std::floor(p.y / cell)))];
            if (c.empty() || c.back() != int(i)) c.push_back(int(i));
        }
    }
    std::vector<char> t(g.nodes.size(), 0);
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
        const Node& node = g.nodes[n];
        if (node.ends.size() != 2) continue;
        const glm::vec2 at = node.sum / float(node.count);
        const int cx = int(std::floor(at.x / cell)), cy = int(std::floor(at.y / cell));
        for (int dy = -1; dy <= 1 && !t[n]; ++dy)
            for (int dx = -1; dx <= 1 && !t[n]; ++dx) {
                const auto it = grid.find(cell_key(cx + dx, cy + dy));
                if (it == grid.end()) continue;
                for (const int i : it->second) {
                    if (i == node.ends[0] / 2 || i == node.ends[1] / 2) continue;
                    for (const glm::vec2& p : ps[std::size_t(i)].points)
                        if (glm::length(p - at) <= tol) {
                            t[n] = 1;
                            break;
                        }
                    if (t[n]) break;
                }
            }
    }
    return t;
}

// Which ends continue through each node: both of a node of two ends unless it turns more than
// max_turn_deg (or, with occlusion, is a T); with occlusion, the nearest pair of a node of more.
void mark_through(Graph& g, const ChainParams& p, const std::vector<float>& depth_at_end) {
    const float cos_limit = std::cos(glm::radians(180.0f - std::min(p.max_turn_deg, 180.0f)));
    const std::vector<char> t = p.occlusion ? t_nodes(g, p.tolerance) : std::vector<char>(g.nodes.size(), 0);
    const auto& ps = *g.pieces;
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
        Node& n = g.nodes[k];
        if (n.ends.size() == 2) {
            if (t[k]) continue;
            if (p.max_turn_deg < 180.0f) {
                glm::vec2 a = leaving_dir(ps[n.ends[0] / 2], n.ends[0] % 2 == 0);
                glm::vec2 b = leaving_dir(ps[n.ends[1] / 2], n.ends[1] % 2 == 0);
                if (glm::dot(a, b) > cos_limit) continue;  // angle between leaving directions too small
            }
            n.through[0] = n.ends[0], n.through[1] = n.ends[1];
        } else if (p.occlusion && n.ends.size() >= 3) {
            float best = 0.0f, best_dot = 0.0f;
            for (std::size_t i = 0; i < n.ends.size(); ++i)
                for (std::size_t j = i + 1; j < n.ends.size(); ++j) {
                    const int a = n.ends[i], b = n.ends[j];
                    if (a / 2 == b / 2) continue;  // both ends of one piece: a loop
                    const float da = depth_at_end[std::size_t(a)], db = depth_at_end[std::size_t(b)];
                    if (!(da > 0.0f && db > 0.0f) || std::abs(da - db) > 0.1f * std::min(da, db)) continue;
                    const float far = std::max(da, db);
                    const float dot = glm::dot(leaving_dir(ps[std::size_t(a / 2)], a % 2 == 0),
                                               leaving_dir(ps[std::size_t(b / 2)], b % 2 == 0));
                    const bool nearer = n.through[0] < 0 || far < 0.99f * best;
                    const bool as_near_straighter = far <= 1.01f * best && dot < best_dot;
                    if (nearer || as_near_straighter) n.through[0] = a, n.through[1] = b, best = far, best_dot = dot;
                }
        }
    }
}

// Appends piece p (entered at end id e) to out, oriented away from that end.
void append_piece(const Graph& g, int e, Stroke& out) {
    const Stroke& s = (*g.pieces)[e / 2];
    std::size_t n = s.points.size();
    for (std::size_t k = out.points.empty() ? 0 : 1; k < n; ++k) {
        std::size_t i = e % 2 == 0 ? k : n - 1 - k;
        out.points.push_back(s.points[i]);
        out.depth.push_back(s.depth[i]);
        if (g.weighted) out.weight.push_back(weight_at(s, i));
    }
}

Stroke walk(Graph& g, int node, int e, StrengthRule rule) {
    Stroke out;
    out.kind = (*g.pieces)[e / 2].kind;
    float sum = 0.0f, mx = 0.0f;
    int count = 0;
    const int start = node;
    while (true) {
        const Stroke& s = (*g.pieces)[e / 2];
        g.used[e / 2] = 1;
        append_piece(g, e, out);
        sum += s.strength, mx = std::max(mx, s.strength), ++count;
        node = g.node_of[e ^ 1];
        const Node& n = g.nodes[node];
        if (!n.passes(e ^ 1) || node == start) break;
        const int next = n.other(e ^ 1);
        if (g.used[next / 2]) break;
        e = next;
    }
    out.strength = rule == StrengthRule::max ? mx : sum / float(count);
    return out;
}

// Chains one group of open pieces (all of one kind).
std::vector<Stroke> chain_group(std::vector<Stroke>& pieces, const ChainParams& p) {
    Graph g;
    g.pieces = &pieces;
    for (const Stroke& s : pieces) g.weighted |= !s.weight.empty();
    std::vector<glm::vec2> ends;
    for (const Stroke& s : pieces) ends.push_back(s.points.front()), ends.push_back(s.points.back());
    g.node_of = cluster_ends(ends, p.tolerance, g.nodes);
    std::vector<float> depth_at_end(ends.size(), 0.0f);
    if (p.occlusion)
        for (std::size_t e = 0; e < ends.size(); ++e) depth_at_end[e] = end_depth(pieces[e / 2], int(e));
    for (std::size_t e = 0; e < ends.size(); ++e) {
        Node& n = g.nodes[g.node_of[e]];
        n.sum += ends[e], ++n.count;
        n.depth_sum += e % 2 == 0 ? pieces[e / 2].depth.front() : pieces[e / 2].depth.back();
    }
    g.used.assign(pieces.size(), 0);
    for (std::size_t i = 0; i < pieces.size(); ++i) {  // snap ends, drop collapsed/repeated pieces
        int a = g.node_of[2 * i], b = g.node_of[2 * i + 1];
        for (int e : {2 * int(i), 2 * int(i) + 1}) {
            const Node& n = g.nodes[g.node_of[e]];
            std::size_t k = e % 2 == 0 ? 0 : pieces[i].points.size() - 1;
            pieces[i].points[k] = n.sum / float(n.count);
            pieces[i].depth[k] = n.depth_sum / float(n.count);
        }
        bool collapsed = a == b && pieces[i].points.size() == 2;
        bool repeated = false;
        if (pieces[i].points.size() == 2)
            for (int e : g.nodes[a].ends) {
                const Stroke& o = pieces[e / 2];
                repeated |= o.points.size() == 2 && g.node_of[e ^ 1] == b && !g.used[e / 2];
            }
        if (collapsed || repeated) {
            g.used[i] = 1;
            continue;
        }
        g.nodes[a].ends.push_back(2 * int(i));
        g.nodes[b].ends.push_back(2 * int(i) + 1);
    }
    mark_through(g, p, depth_at_end);
    std::vector<Stroke> out;
    for (std::size_t n = 0; n < g.nodes.size(); ++n)
        for (int e : g.nodes[n].ends)
            if (!g.nodes[n].passes(e) && !g.used[e / 2]) out.push_back(walk(g, int(n), e, p.strength));
    for (std::size_t i = 0; i < pieces.size(); ++i)
        if (!g.used[i]) out.push_back(walk(g, g.node_of[2 * i], 2 * int(i), p.strength));
    return out;
}

}  // namespace

std::vector<Stroke> chain_segments(const std::vector<ImageSegment>& segments, const ChainParams& params) {
    std::vector<Stroke> pieces;
    pieces.reserve(segments.size());
    for (const ImageSegment& s : segments)
        pieces.push_back(Stroke{{s.a, s.b}, {s.depth_a, s.depth_b}, s.strength, params.kind, {}});
    return chain_group(pieces, params);
}

std::vector<Stroke> join_strokes(std::vector<Stroke> strokes, const ChainParams& params) {
    std::vector<std::string> kinds;
    for (const Stroke& s : strokes)
        if (std::find(kinds.begin(), kinds.end(), s.kind) == kinds.end()) kinds.push_back(s.kind);
    std::vector<Stroke> out;
    for (const std::string& kind : kinds) {
        std::vector<Stroke> open;
        for (Stroke& s : strokes) {
            if (s.kind != kind || s.points.empty()) continue;
            if (s.depth.size() != s.points.size()) s.depth.resize(s.points.size(), 0.0f);
            if (is_closed(s) || s.points.size() < 2) out.push_back(std::move(s));
            else open.push_back(std::move(s));
        }
        for (Stroke& s : chain_group(open, params)) out.push_back(std::move(s));
    }
    return out;
}

std::vector<Stroke> join_strokes(std::vector<Stroke> strokes, float tolerance) {
    ChainParams p;
    p.tolerance = tolerance;
    return join_strokes(std::move(strokes), p);
}

}  // namespace penink
