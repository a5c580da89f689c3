#include "drainage/line_set.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/common.hpp>

#include "core/parallel_chunks.hpp"
#include "drainage/line_chunks.hpp"

namespace penink {

namespace {

constexpr std::size_t max_levels = 40;

float level_side(const LineIndex& x, std::size_t k) { return std::ldexp(x.cell, int(k)); }

// The cell of a level a value falls in, clamped to [0, n).
std::uint32_t cell_of(double v, double origin, double side, std::uint32_t n) {
    const double f = std::floor((v - origin) / side);
    return std::uint32_t(std::clamp(f, 0.0, double(n - 1)));
}

}  // namespace

void index_lines(DrapedLineSet& set) {
    LineIndex& x = set.index;
    x = LineIndex{};
    // each line's box and length on all cores (chunks of equal shares of the vertices), then the
    // set's box over the lines in order
    parallel_line_chunks(set.lines, set.vertices.size(), 0, set.lines.size(), 1 << 14, [&](std::size_t l0, std::size_t l1) {
        for (std::size_t i = l0; i < l1; ++i) {
            DrapedLine& l = set.lines[i];
            const DrapedVertex* v = set.vertices.data() + l.first;
            l.lo = l.hi = glm::vec2(v[0].x, v[0].y);
            double length = 0.0;
            for (std::uint32_t k = 1; k < l.count; ++k) {
                l.lo = glm::min(l.lo, glm::vec2(v[k].x, v[k].y)), l.hi = glm::max(l.hi, glm::vec2(v[k].x, v[k].y));
                const double dx = double(v[k].x) - v[k - 1].x, dy = double(v[k].y) - v[k - 1].y,
                             dz = double(v[k].z) - v[k - 1].z;
                length += std::sqrt(dx * dx + dy * dy + dz * dz);
            }
            l.length = float(length);
        }
    });
    glm::vec2 lo(0.0f), hi(0.0f);
    for (std::size_t i = 0; i < set.lines.size(); ++i) {
        const DrapedLine& l = set.lines[i];
        lo = i ? glm::min(lo, l.lo) : l.lo, hi = i ? glm::max(hi, l.hi) : l.hi;
    }
    x.start.assign(1, 0);
    if (set.lines.empty()) return;
    x.origin = lo;
    const double span = std::max(double(hi.x) - lo.x, double(hi.y) - lo.y);
    // about 8 lines a level-0 cell on average, at most 1024 cells along the longer side
    const double across = std::clamp(std::ceil(std::sqrt(double(set.lines.size()) / 8.0)), 1.0, 1024.0);
    x.cell = span > 0.0 && std::isfinite(span) ? float(span / across) : 1.0f;
    if (!(x.cell > 0.0f) || !std::isfinite(x.cell)) x.cell = 1.0f;
    for (std::size_t k = 0;; ++k) {
        const double side = level_side(x, k);
        x.level_cols.push_back(std::uint32_t(std::floor((double(hi.x) - lo.x) / side)) + 1);
        x.level_rows.push_back(std::uint32_t(std::floor((double(hi.y) - lo.y) / side)) + 1);
        if (side >= span || k + 1 == max_levels) break;
    }
    std::vector<std::size_t> level_start(x.level_cols.size() + 1, 0);
    for (std::size_t k = 0; k < x.level_cols.size(); ++k)
        level_start[k + 1] = level_start[k] + std::size_t(x.level_cols[k]) * x.level_rows[k];
    std::vector<std::uint32_t> cell(set.lines.size());
    std::vector<std::uint32_t> count(level_start.back() + 1, 0);
    for (std::size_t i = 0; i < set.lines.size(); ++i) {
        const DrapedLine& l = set.lines[i];
        const double extent = std::max(double(l.hi.x) - l.lo.x, double(l.hi.y) - l.lo.y);
        std::size_t k = 0;
        while (k + 1 < x.level_cols.size() && double(level_side(x, k)) < extent) ++k;
        const double side = level_side(x, k);
        const double cx = 0.5 * (double(l.lo.x) + l.hi.x), cy = 0.5 * (double(l.lo.y) + l.hi.y);
        cell[i] = std::uint32_t(level_start[k] + std::size_t(cell_of(cy, lo.y, side, x.level_rows[k])) * x.level_cols[k] +
                                cell_of(cx, lo.x, side, x.level_cols[k]));
        ++count[cell[i] + 1];
    }
    for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    x.start = count;
    x.ids.resize(set.lines.size());
    for (std::size_t i = 0; i < set.lines.size(); ++i) x.ids[count[cell[i]]++] = std::uint32_t(i);
}

std::vector<std::uint32_t> lines_meeting_box(const DrapedLineSet& set, glm::vec2 lo, glm::vec2 hi) {
    std::vector<std::uint32_t> out;
    const LineIndex& x = set.index;
    if (!(lo.x <= hi.x && lo.y <= hi.y)) return out;
    std::size_t base = 0;
    for (std::size_t k = 0; k < x.level_cols.size(); ++k) {
        const double side = level_side(x, k);
        const std::uint32_t nc = x.level_cols[k], nr = x.level_rows[k];
        // a line's box lies within its cell grown by side / 2; a cell more is allowed for rounding
        auto first = [&](double v, double o, std::uint32_t n) {
            return std::uint32_t(std::clamp(std::floor((v - o) / side) - 2.0, 0.0, double(n - 1)));
        };
        auto last = [&](double v, double o, std::uint32_t n) {
            return std::uint32_t(std::clamp(std::floor((v - o) / side) + 1.0, 0.0, double(n - 1)));
        };
        const double ox = x.origin.x, oy = x.origin.y;
        if (double(hi.x) < ox - 2.0 * side || double(hi.y) < oy - 2.0 * side ||
            double(lo.x) > ox + (nc + 1.0) * side || double(lo.y) > oy + (nr + 1.0) * side) {
            base += std::size_t(nc) * nr;
            continue;
        }
        const std::uint32_t c0 = first(lo.x, ox, nc), c1 = last(hi.x, ox, nc);
        const std::uint32_t r0 = first(lo.y, oy, nr), r1 = last(hi.y, oy, nr);
        for (std::uint32_t r = r0; r <= r1; ++r)
            for (std::uint32_t c = c0; c <= c1; ++c) {
                const std::size_t at = base + std::size_t(r) * nc + c;
                for (std::uint32_t j = x.start[at]; j < x.start[at + 1]; ++j) {
                    const DrapedLine& l = set.lines[x.ids[j]];
                    if (l.lo.x <= hi.x && l.hi.x >= lo.x && l.lo.y <= hi.y && l.hi.y >= lo.y) out.push_back(x.ids[j]);
                }
            }
        base += std::size_t(nc) * nr;
    }
    if (out.size() < set.lines.size() / 32) {
        std::sort(out.begin(), out.end());
        return out;
    }
    // many: in ascending order through a bit per line (a pass over n / 64 words, no sort)
    std::vector<std::uint64_t> bits((set.lines.size() + 63) / 64, 0);
    for (const std::uint32_t id : out) bits[id >> 6] |= std::uint64_t(1) << (id & 63);
    out.clear();
    for (std::size_t w = 0; w < bits.size(); ++w)
        for (std::uint64_t b = bits[w]; b; b &= b - 1) out.push_back(std::uint32_t(w * 64 + std::countr_zero(b)));
    return out;
}

bool line_set_ok(const DrapedLineSet& set) { return line_set_ok(set, set.vertices.size()); }

bool line_set_ok(const DrapedLineSet& set, std::size_t vertex_count) {
    std::size_t next = 0;
    for (const DrapedLine& l : set.lines) {
        if (l.first != next || l.count < 1 || l.count > vertex_count - next) return false;
        next += l.count;
    }
    if (next != vertex_count) return false;
    const LineIndex& x = set.index;
    if (x.level_cols.size() != x.level_rows.size() || x.level_cols.size() > max_levels) return false;
    if (!(x.cell > 0.0f) || !std::isfinite(x.cell)) return false;
    std::size_t cells = 0;
    for (std::size_t k = 0; k < x.level_cols.size(); ++k) {
        if (x.level_cols[k] < 1 || x.level_rows[k] < 1) return false;
        const std::size_t n = std::size_t(x.level_cols[k]) * x.level_rows[k];
        if (n > x.start.size()) return false;  // bounds cells by what was read
        cells += n;
    }
    if (x.start.size() != cells + 1 || x.start[0] != 0 || x.start.back() != x.ids.size() ||
        x.ids.size() != set.lines.size())
        return false;
    for (std::size_t c = 0; c < cells; ++c)
        if (x.start[c] > x.start[c + 1]) return false;
    std::vector<std::uint8_t> seen(set.lines.size(), 0);
    for (std::uint32_t id : x.ids) {
        if (id >= set.lines.size() || seen[id]) return false;
        seen[id] = 1;
    }
    return true;
}

}  // namespace penink
