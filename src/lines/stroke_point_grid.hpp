// Points of strokes hashed by square cells (image pixels): whether a point of another stroke lies
// within r of a point, looking at the 3 x 3 cells around it (r at most the cell side). Used by
// the doubled-line merge (doubled_lines.hpp) and its measure (line_metrics.hpp).
#pragma once
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace penink {

class StrokePointGrid {
public:
    explicit StrokePointGrid(float cell) : cell_(cell) {}
    void add(glm::vec2 p, int stroke) { cells_[key(cell_of(p.x), cell_of(p.y))].push_back({p, stroke}); }
    // A point of a stroke other than `stroke` within r of p (inclusive).
    bool near_other(glm::vec2 p, int stroke, float r) const {
        const int cx = cell_of(p.x), cy = cell_of(p.y);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const auto it = cells_.find(key(cx + dx, cy + dy));
                if (it == cells_.end()) continue;
                for (const Entry& e : it->second)
                    if (e.stroke != stroke && glm::length(e.p - p) <= r) return true;
            }
        return false;
    }

private:
    struct Entry {
        glm::vec2 p;
        int stroke;
    };
    int cell_of(float v) const { return int(std::floor(v / cell_)); }
    static std::uint64_t key(int x, int y) { return (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y); }
    float cell_;
    std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
};

}  // namespace penink
