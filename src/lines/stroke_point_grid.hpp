// Points of strokes hashed by square cells (image pixels): whether a point of another stroke lies
// within r of a point, looking at the 3 x 3 cells around it (r at most the cell side). Used by
// the doubled-line merge (doubled_lines.hpp) and its measure (line_metrics.hpp).
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace penink {

class StrokePointGrid {
public:
    explicit StrokePointGrid(float cell) : cell_(cell) { slots_.assign(std::size_t(1) << shift_bits(), Slot{}); }
    void add(glm::vec2 p, int stroke) { cell(key(cell_of(p.x), cell_of(p.y))).push_back({p, stroke}); }
    // A point of a stroke other than `stroke` within r of p (inclusive).
    bool near_other(glm::vec2 p, int stroke, float r) const {
        // A squared distance over (1.001 r)^2 is farther than r however the square root rounds:
        // skipped before the exact test, which decides as it always did.
        const float far = (r * 1.001f) * (r * 1.001f);
        const int cx = cell_of(p.x), cy = cell_of(p.y);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const std::vector<Entry>* c = find(key(cx + dx, cy + dy));
                if (!c) continue;
                for (const Entry& e : *c) {
                    if (e.stroke == stroke) continue;
                    const glm::vec2 d = e.p - p;
                    if (d.x * d.x + d.y * d.y > far) continue;
                    if (glm::length(d) <= r) return true;
                }
            }
        return false;
    }

private:
    struct Entry {
        glm::vec2 p;
        int stroke;
    };
    static constexpr std::uint32_t kEmpty = 0xffffffffu;
    struct Slot {  // open addressing, linear probing: a cell's key and its index in cells_
        std::uint64_t key = 0;
        std::uint32_t cell = kEmpty;
    };
    int cell_of(float v) const { return int(std::floor(v / cell_)); }
    static std::uint64_t key(int x, int y) { return (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y); }
    static int shift_bits() { return 10; }  // 1024 slots to start
    std::size_t slot_of(std::uint64_t k) const {  // Fibonacci hashing: the product's top bits
        return std::size_t((k * 0x9E3779B97F4A7C15ull) >> (64 - bits_));
    }
    const std::vector<Entry>* find(std::uint64_t k) const {
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = slot_of(k);; i = (i + 1) & mask) {
            if (slots_[i].cell == kEmpty) return nullptr;
            if (slots_[i].key == k) return &cells_[slots_[i].cell];
        }
    }
    std::vector<Entry>& cell(std::uint64_t k) {
        const std::size_t mask = slots_.size() - 1;
        std::size_t i = slot_of(k);
        for (; slots_[i].cell != kEmpty; i = (i + 1) & mask)
            if (slots_[i].key == k) return cells_[slots_[i].cell];
        if (2 * (cells_.size() + 1) > slots_.size()) {  // at most half full
            grow();
            return cell(k);
        }
        slots_[i] = {k, std::uint32_t(cells_.size())};
        cells_.emplace_back();
        return cells_.back();
    }
    void grow() {
        const std::vector<Slot> old = std::move(slots_);
        ++bits_;
        slots_.assign(std::size_t(1) << bits_, Slot{});
        const std::size_t mask = slots_.size() - 1;
        for (const Slot& s : old) {
            if (s.cell == kEmpty) continue;
            std::size_t i = slot_of(s.key);
            while (slots_[i].cell != kEmpty) i = (i + 1) & mask;
            slots_[i] = s;
        }
    }
    float cell_;
    int bits_ = shift_bits();
    std::vector<Slot> slots_;
    std::vector<std::vector<Entry>> cells_;
};

}  // namespace penink
