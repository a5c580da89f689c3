#include "lines/thin_mask.hpp"

#include <bit>

#include "core/error.hpp"

namespace penink {

int neighbour_count(std::uint8_t code) { return std::popcount(code); }

int connectivity_number(std::uint8_t code) {
    auto off = [code](int k) { return ((code >> (k & 7)) & 1) ? 0 : 1; };
    int c = 0;
    for (int k = 0; k < 8; k += 2) c += off(k) - off(k) * off(k + 1) * off(k + 2);
    return c;
}

namespace {

// Zhang-Suen transition count A(P): 0 -> 1 changes around N, NE, ..., NW, N.
int transitions(std::uint8_t code) {
    int a = 0;
    for (int k = 0; k < 8; ++k) a += !((code >> k) & 1) && ((code >> ((k + 1) & 7)) & 1);
    return a;
}

// Tip of a line: one neighbour, or two neighbours next to each other around the ring (the end
// of a 2-px diagonal). Deleting tips would erode lines from their ends, so they are kept.
bool is_tip(std::uint8_t c) {
    int b = neighbour_count(c);
    if (b == 1) return true;
    std::uint8_t rot = static_cast<std::uint8_t>((c << 1) | (c >> 7));
    return b == 2 && (c & rot) != 0;
}

// Simple (Yokoi number 1: no connectivity change) and not a tip.
bool removable_code(std::uint8_t c) {
    return neighbour_count(c) >= 2 && connectivity_number(c) == 1 && !is_tip(c);
}

// Padded working copy: 1-pixel border of zeros so neighbour reads never leave the buffer.
struct Grid {
    int w2 = 0;
    std::vector<std::uint8_t> px;
    std::array<int, 8> off{};
    std::vector<int> on;  // padded indices of set pixels, scan order

    explicit Grid(const PixelMask& m) : w2(m.width + 2), px(std::size_t(m.width + 2) * (m.height + 2), 0) {
        for (int k = 0; k < 8; ++k) off[k] = neighbour_dy[k] * w2 + neighbour_dx[k];
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x)
                if (m.on[std::size_t(y) * m.width + x]) {
                    int i = (y + 1) * w2 + x + 1;
                    px[i] = 1;
                    on.push_back(i);
                }
    }
    std::uint8_t code(int i) const {
        std::uint8_t c = 0;
        for (int k = 0; k < 8; ++k) c |= std::uint8_t((px[i + off[k]] != 0) << k);
        return c;
    }
    bool removable(int i) const { return removable_code(code(i)); }
    void compact() {
        std::size_t n = 0;
        for (int i : on)
            if (px[i]) on[n++] = i;
        on.resize(n);
    }
    PixelMask to_mask(int w, int h) const {
        PixelMask m{w, h, std::vector<std::uint8_t>(std::size_t(w) * h, 0)};
        for (int i : on) m.on[std::size_t(i / w2 - 1) * w + (i % w2 - 1)] = 1;
        return m;
    }
};

bool zs_candidate(std::uint8_t c, int pass) {
    int b = neighbour_count(c);
    if (b < 2 || b > 6 || transitions(c) != 1) return false;
    bool n = c & 1, e = c & 4, s = c & 16, w = c & 64;
    return pass == 0 ? !(n && e && s) && !(e && s && w) : !(n && e && w) && !(n && s && w);
}

bool zs_subiteration(Grid& g, int pass) {
    std::vector<int> cand;
    for (int i : g.on)
        if (zs_candidate(g.code(i), pass)) cand.push_back(i);
    bool changed = false;
    for (int i : cand)
        if (g.removable(i)) g.px[i] = 0, changed = true;
    if (changed) g.compact();
    return changed;
}

bool cleanup_pass(Grid& g) {
    bool changed = false;
    for (int i : g.on)
        if (g.px[i] && g.removable(i)) g.px[i] = 0, changed = true;
    if (changed) g.compact();
    return changed;
}

}  // namespace

PixelMask thin_mask(const PixelMask& mask) {
    check_mask(mask, "line mask");
    Grid g(mask);
    for (bool changed = true; changed;) {
        bool a = zs_subiteration(g, 0);
        bool b = zs_subiteration(g, 1);
        changed = a || b;
    }
    while (cleanup_pass(g)) {
    }
    return g.to_mask(mask.width, mask.height);
}

namespace {

// Pixels of the branch from end point i up to (not including) the first junction; empty when
// the branch is longer than max_len or ends without reaching a junction.
std::vector<int> spur_from(const Grid& g, int i, int max_len) {
    std::vector<int> branch{i};
    int prev = -1, cur = i;
    while (static_cast<int>(branch.size()) <= max_len) {
        int next = -1, count = 0;
        for (int k = 0; k < 8; ++k) {
            int j = cur + g.off[k];
            if (g.px[j] && j != prev) next = j, ++count;
        }
        if (count != 1) return {};
        if (neighbour_count(g.code(next)) >= 3) return branch;
        prev = cur, cur = next;
        branch.push_back(cur);
    }
    return {};
}

}  // namespace

void prune_spurs(PixelMask& skeleton, int max_len) {
    check_mask(skeleton, "skeleton");
    if (max_len <= 0) return;
    Grid g(skeleton);
    std::vector<std::vector<int>> spurs;
    for (int i : g.on)
        if (neighbour_count(g.code(i)) == 1) {
            std::vector<int> b = spur_from(g, i, max_len);
            if (!b.empty()) spurs.push_back(std::move(b));
        }
    for (const auto& b : spurs)
        for (int i : b) g.px[i] = 0;
    g.compact();
    while (cleanup_pass(g)) {
    }
    skeleton = g.to_mask(skeleton.width, skeleton.height);
}

}  // namespace penink
