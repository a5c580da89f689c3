#include "input/terrain_window.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace penink {

namespace {

// Bit i set when the clip-space point is outside plane i (x<-w, x>w, y<-w, y>w, z<-w, z>w).
std::uint8_t outcode(const glm::dvec4& c) {
    return std::uint8_t((c.x < -c.w) | (c.x > c.w) << 1 | (c.y < -c.w) << 2 | (c.y > c.w) << 3 |
                        (c.z < -c.w) << 4 | (c.z > c.w) << 5);
}

std::vector<std::uint8_t> node_outcodes(const Terrain& t, const glm::dmat4& vp) {
    std::vector<std::uint8_t> out(t.size(), 0x3f);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const glm::dvec4 c = vp * glm::dvec4(glm::dvec3(t.pos[i]), 1.0);
        out[i] = outcode(c);
        if (out[i] == 0 && !(c.w > 0.0)) out[i] = 0x3f;  // degenerate: on the eye
    }
    return out;
}

struct Box {
    int c0 = 1 << 30, r0 = 1 << 30, c1 = -1, r1 = -1;  // inclusive node bounds
    void add(int ca, int ra, int cb, int rb) {
        c0 = std::min(c0, ca), r0 = std::min(r0, ra), c1 = std::max(c1, cb), r1 = std::max(r1, rb);
    }
    bool empty() const { return c1 < c0; }
};

// Adds the cell with upper-left node (c, r) when it may cross the view.
void add_cell(const Terrain& t, const std::vector<std::uint8_t>& code, int c, int r, Box& box) {
    const std::size_t idx[4] = {t.index(c, r), t.index(c + 1, r), t.index(c, r + 1), t.index(c + 1, r + 1)};
    int n = 0;
    std::uint8_t all = 0x3f, any = 0;
    for (std::size_t i : idx) {
        if (!t.valid[i]) continue;
        ++n, all &= code[i], any |= code[i];
    }
    if (n < 3 || all != 0) return;       // no triangle, or all outside the same plane
    if (any == 0) box.add(c, r, c + 1, r + 1);  // wholly inside
    else box.add(c - 1, r - 1, c + 2, r + 2);   // straddles: keep its neighbours too
}

}  // namespace

GridWindow visible_window(const Terrain& t, const glm::dmat4& view_projection, int margin_nodes) {
    const std::vector<std::uint8_t> code = node_outcodes(t, view_projection);
    Box box;
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c)
            if (t.valid[t.index(c, r)] && code[t.index(c, r)] == 0) box.add(c, r, c, r);
    for (int r = 0; r + 1 < t.rows; ++r)
        for (int c = 0; c + 1 < t.cols; ++c) add_cell(t, code, c, r, box);
    if (box.empty()) return {};
    const int m = std::max(margin_nodes, 0);
    GridWindow w;
    w.c0 = std::max(box.c0 - m, 0), w.r0 = std::max(box.r0 - m, 0);
    w.c1 = std::min(box.c1 + 1 + m, t.cols), w.r1 = std::min(box.r1 + 1 + m, t.rows);
    return w;
}

}  // namespace penink
