#include "lines/trace_mask_outline.hpp"

#include <cmath>
#include <cstdint>

#include "lines/simplify.hpp"

namespace penink {

namespace {

// Directions of boundary edges between pixel corners: bit values and steps (y down).
enum : std::uint8_t { kE = 1, kS = 2, kW = 4, kN = 8 };
constexpr int dir_dx(std::uint8_t d) { return d == kE ? 1 : d == kW ? -1 : 0; }
constexpr int dir_dy(std::uint8_t d) { return d == kS ? 1 : d == kN ? -1 : 0; }
// Right turn in the y-down frame (the covered pixels lie on the right of every edge).
constexpr std::uint8_t right_of(std::uint8_t d) {
    return d == kE ? kS : d == kS ? kW : d == kW ? kN : kE;
}

struct Corners {
    int w1 = 0;                       // corners per row (mask width + 1)
    std::vector<std::uint8_t> out;    // outgoing edge directions per corner
    std::vector<std::uint8_t> used;   // directions already traced
};

Corners boundary_edges(const PixelMask& m) {
    Corners c;
    c.w1 = m.width + 1;
    c.out.assign(std::size_t(c.w1) * (m.height + 1), 0);
    c.used = c.out;
    auto on = [&m](int x, int y) {
        return x >= 0 && y >= 0 && x < m.width && y < m.height && m.on[std::size_t(y) * m.width + x];
    };
    auto at = [&c](int x, int y) -> std::uint8_t& { return c.out[std::size_t(y) * c.w1 + x]; };
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            if (!on(x, y)) continue;
            if (!on(x, y - 1)) at(x, y) |= kE;
            if (!on(x + 1, y)) at(x + 1, y) |= kS;
            if (!on(x, y + 1)) at(x + 1, y + 1) |= kW;
            if (!on(x - 1, y)) at(x, y + 1) |= kN;
        }
    return c;
}

// Outgoing direction at corner v when arriving heading d (saddles: turn right).
std::uint8_t next_dir(const Corners& c, std::size_t v, std::uint8_t d) {
    std::uint8_t bits = c.out[v];
    if (bits == kE || bits == kS || bits == kW || bits == kN) return bits;
    return right_of(d);
}

std::uint8_t first_dir(std::uint8_t bits) {
    for (std::uint8_t d : {kE, kS, kW, kN})
        if (bits & d) return d;
    return 0;
}

// Follows one ring from corner v0 leaving along d0; records the corners where it turns.
Ring follow(Corners& c, std::size_t v0, std::uint8_t d0) {
    Ring ring;
    std::size_t v = v0;
    std::uint8_t d = d0;
    do {
        c.used[v] |= d;
        int x = static_cast<int>(v % c.w1) + dir_dx(d), y = static_cast<int>(v / c.w1) + dir_dy(d);
        v = std::size_t(y) * c.w1 + x;
        std::uint8_t nd = next_dir(c, v, d);
        if (nd != d) ring.emplace_back(static_cast<float>(x), static_cast<float>(y));
        d = nd;
    } while (!(v == v0 && d == d0));
    if (ring.size() > 1) ring.insert(ring.begin(), ring.back()), ring.pop_back();
    return ring;
}

}  // namespace

std::vector<Ring> trace_mask_outline(const PixelMask& mask, float tolerance) {
    check_mask(mask, "coverage mask");
    Corners c = boundary_edges(mask);
    std::vector<Ring> rings;
    for (std::size_t v = 0; v < c.out.size(); ++v) {
        for (std::uint8_t free = c.out[v] & ~c.used[v]; free; free = c.out[v] & ~c.used[v]) {
            Ring r = follow(c, v, first_dir(free));
            if (tolerance > 0.0f) r = simplify_ring(remove_collinear(r), tolerance);
            if (r.size() >= 3) rings.push_back(std::move(r));
        }
    }
    return rings;
}

}  // namespace penink
