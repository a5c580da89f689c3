#include "lines/trace_pixel_lines.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "lines/thin_mask.hpp"

namespace penink {

namespace {

enum : std::uint8_t { kOff = 0, kOn = 1, kUsed = 2, kJunction = 3 };

// Padded skeleton with pixel states, junction clusters and their centres.
struct Skeleton {
    int w2 = 0;
    std::vector<std::uint8_t> px;
    std::array<int, 8> off{};
    std::vector<int> on;         // padded indices, scan order
    std::vector<int> junctions;  // sorted padded indices of junction pixels
    std::vector<int> cluster;    // cluster id per junctions[] entry
    std::vector<glm::vec2> centre;

    glm::ivec2 xy(int i) const { return {i % w2 - 1, i / w2 - 1}; }
    glm::vec2 centre_of_pixel(int i) const { return glm::vec2(xy(i)) + 0.5f; }
    int degree(int i) const {
        int n = 0;
        for (int k = 0; k < 8; ++k) n += px[i + off[k]] != kOff;
        return n;
    }
    int cluster_of(int i) const {
        auto it = std::lower_bound(junctions.begin(), junctions.end(), i);
        return cluster[static_cast<std::size_t>(it - junctions.begin())];
    }
};

void label_clusters(Skeleton& s) {
    s.cluster.assign(s.junctions.size(), -1);
    for (std::size_t j = 0; j < s.junctions.size(); ++j) {
        if (s.cluster[j] >= 0) continue;
        int id = static_cast<int>(s.centre.size());
        glm::vec2 sum(0.0f);
        int count = 0;
        std::vector<std::size_t> todo{j};
        s.cluster[j] = id;
        while (!todo.empty()) {
            std::size_t t = todo.back();
            todo.pop_back();
            sum += s.centre_of_pixel(s.junctions[t]), ++count;
            for (int k = 0; k < 8; ++k) {
                int n = s.junctions[t] + s.off[k];
                auto it = std::lower_bound(s.junctions.begin(), s.junctions.end(), n);
                if (it == s.junctions.end() || *it != n) continue;
                std::size_t u = static_cast<std::size_t>(it - s.junctions.begin());
                if (s.cluster[u] < 0) s.cluster[u] = id, todo.push_back(u);
            }
        }
        s.centre.push_back(sum / static_cast<float>(count));
    }
}

Skeleton make_skeleton(const PixelMask& m) {
    Skeleton s;
    s.w2 = m.width + 2;
    s.px.assign(std::size_t(m.width + 2) * (m.height + 2), kOff);
    for (int k = 0; k < 8; ++k) s.off[k] = neighbour_dy[k] * s.w2 + neighbour_dx[k];
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            if (m.on[std::size_t(y) * m.width + x]) {
                int i = (y + 1) * s.w2 + x + 1;
                s.px[i] = kOn;
                s.on.push_back(i);
            }
    for (int i : s.on)
        if (s.degree(i) >= 3) s.junctions.push_back(i);
    for (int i : s.junctions) s.px[i] = kJunction;
    label_clusters(s);
    return s;
}

void push(PixelChain& c, const Skeleton& s, glm::vec2 p, int pixel) {
    if (!c.points.empty() && c.points.back() == p) return;
    c.points.push_back(p);
    c.pixel.push_back(s.xy(pixel));
}

void push_pixel(PixelChain& c, const Skeleton& s, int i) {
    push(c, s, s.centre_of_pixel(i), i);
    ++c.pixel_count;
}

// Next unused on-pixel around cur other than prev, else a junction pixel; -1 when none.
int next_pixel(const Skeleton& s, int cur, int prev) {
    int junction = -1;
    for (int k = 0; k < 8; ++k) {
        int j = cur + s.off[k];
        if (j == prev) continue;
        if (s.px[j] == kOn) return j;
        if (s.px[j] == kJunction && junction < 0) junction = j;
    }
    return junction;
}

// Walks from start (an end point, a junction pixel or a loop pixel) through first.
PixelChain walk(Skeleton& s, int start, int first) {
    PixelChain c;
    if (s.px[start] == kJunction) push(c, s, s.centre[s.cluster_of(start)], start);
    push_pixel(c, s, start);
    if (s.px[start] == kOn) s.px[start] = kUsed;
    int prev = start, cur = first;
    while (cur >= 0) {
        if (s.px[cur] == kJunction) {
            push_pixel(c, s, cur);
            push(c, s, s.centre[s.cluster_of(cur)], cur);
            break;
        }
        if (cur == start) {  // closed loop
            push(c, s, s.centre_of_pixel(cur), cur);
            c.closed = true;
            break;
        }
        push_pixel(c, s, cur);
        s.px[cur] = kUsed;
        int next = next_pixel(s, cur, prev);
        if (next < 0 && prev != start && s.px[start] == kUsed && s.degree(start) == 2) {
            for (int k = 0; k < 8; ++k)
                if (cur + s.off[k] == start) next = start;
        }
        prev = cur, cur = next;
    }
    return c;
}

}  // namespace

std::vector<PixelChain> chain_skeleton(const PixelMask& skeleton, int min_pixels) {
    check_mask(skeleton, "skeleton");
    Skeleton s = make_skeleton(skeleton);
    std::vector<PixelChain> chains;
    auto keep = [&](PixelChain&& c) {
        if (c.points.size() >= 2 && c.pixel_count >= min_pixels) chains.push_back(std::move(c));
    };
    for (int i : s.on) {
        if (s.px[i] == kOn && s.degree(i) == 1) {
            keep(walk(s, i, next_pixel(s, i, -1)));
        } else if (s.px[i] == kJunction) {
            for (int k = 0; k < 8; ++k)
                if (s.px[i + s.off[k]] == kOn) keep(walk(s, i, i + s.off[k]));
        }
    }
    for (int i : s.on)
        if (s.px[i] == kOn && s.degree(i) == 2) keep(walk(s, i, next_pixel(s, i, -1)));
    return chains;
}

namespace {

// Depths of a chain; unknown values filled from the nearest known point along the chain.
std::vector<float> chain_depth(const PixelChain& c, const DepthImage& d, int radius) {
    std::size_t n = c.points.size();
    std::vector<float> z(n, 0.0f);
    if (is_empty(d)) return z;
    std::vector<int> known;
    for (std::size_t i = 0; i < n; ++i) {
        z[i] = sample_depth(d, c.pixel[i].x, c.pixel[i].y);
        for (int dy = -radius; dy <= radius; ++dy)
            for (int dx = -radius; dx <= radius; ++dx) {
                const int x = c.pixel[i].x + dx, y = c.pixel[i].y + dy;
                if (x < 0 || y < 0 || x >= d.width || y >= d.height) continue;
                const float v = d.depth[std::size_t(y) * std::size_t(d.width) + std::size_t(x)];
                if (std::isfinite(v) && !(v >= z[i])) z[i] = v;
            }
        if (std::isfinite(z[i])) known.push_back(static_cast<int>(i));
    }
    if (known.empty()) return std::vector<float>(n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        if (std::isfinite(z[i])) continue;
        int ii = static_cast<int>(i);
        auto it = std::lower_bound(known.begin(), known.end(), ii);
        int best = it == known.end() ? known.back() : *it;
        if (it != known.begin() && (it == known.end() || ii - *(it - 1) <= *it - ii)) best = *(it - 1);
        z[i] = z[static_cast<std::size_t>(best)];
    }
    return z;
}

}  // namespace

std::vector<Stroke> trace_pixel_lines(const PixelMask& mask, const DepthImage& depth,
                                      const TraceParams& params) {
    check_mask(mask, "line mask");
    if (!is_empty(depth)) {
        check_depth(depth, "depth image");
        if (depth.width != mask.width || depth.height != mask.height)
            throw Error("lines", "",
                        "depth image " + std::to_string(depth.width) + "x" + std::to_string(depth.height) +
                            " does not match line mask " + std::to_string(mask.width) + "x" +
                            std::to_string(mask.height),
                        ExitCode::internal);
    }
    PixelMask skel = params.thin ? thin_mask(mask) : mask;
    prune_spurs(skel, params.max_spur);
    std::vector<Stroke> out;
    for (PixelChain& c : chain_skeleton(skel, params.min_pixels)) {
        Stroke s;
        s.depth = chain_depth(c, depth, std::max(params.depth_radius, 0));
        s.points = std::move(c.points);
        s.strength = params.strength;
        s.kind = params.kind;
        out.push_back(std::move(s));
    }
    return out;
}

}  // namespace penink
