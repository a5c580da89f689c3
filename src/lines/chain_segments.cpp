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
    bool breaks = false;
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
};

glm::vec2 leaving_dir(const Stroke& s, bool from_start) {
    glm::vec2 a = from_start ? s.points.front() : s.points.back();
    glm::vec2 b = from_start ? s.points[1] : s.points[s.points.size() - 2];
    glm::vec2 d = b - a;
    float l = glm::length(d);
    return l > 0.0f ? d / l : d;
}

void mark_breaks(Graph& g, float max_turn_deg) {
    const float cos_limit = std::cos(glm::radians(180.0f - std::min(max_turn_deg, 180.0f)));
    for (Node& n : g.nodes) {
        n.breaks = n.ends.size() != 2;
        if (n.breaks || max_turn_deg >= 180.0f) continue;
        const auto& ps = *g.pieces;
        glm::vec2 a = leaving_dir(ps[n.ends[0] / 2], n.ends[0] % 2 == 0);
        glm::vec2 b = leaving_dir(ps[n.ends[1] / 2], n.ends[1] % 2 == 0);
        n.breaks = glm::dot(a, b) > cos_limit;  // angle between leaving directions too small
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
        if (n.breaks || node == start) break;
        int next = n.ends[0] == (e ^ 1) ? n.ends[1] : n.ends[0];
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
    std::vector<glm::vec2> ends;
    for (const Stroke& s : pieces) ends.push_back(s.points.front()), ends.push_back(s.points.back());
    g.node_of = cluster_ends(ends, p.tolerance, g.nodes);
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
    mark_breaks(g, p.max_turn_deg);
    std::vector<Stroke> out;
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
        if (!g.nodes[n].breaks) continue;
        for (int e : g.nodes[n].ends)
            if (!g.used[e / 2]) out.push_back(walk(g, int(n), e, p.strength));
    }
    for (std::size_t i = 0; i < pieces.size(); ++i)
        if (!g.used[i]) out.push_back(walk(g, g.node_of[2 * i], 2 * int(i), p.strength));
    return out;
}

}  // namespace

std::vector<Stroke> chain_segments(const std::vector<ImageSegment>& segments, const ChainParams& params) {
    std::vector<Stroke> pieces;
    pieces.reserve(segments.size());
    for (const ImageSegment& s : segments)
        pieces.push_back(Stroke{{s.a, s.b}, {s.depth_a, s.depth_b}, s.strength, params.kind});
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
