#include "drainage/band_flood.hpp"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "drainage/flood.hpp"

namespace penink::flood {

FillStats flood_labelled_band(const float* z, const GridShape& g, std::uint8_t* flags, std::uint32_t* level,
                              std::uint32_t* labels, int row0, int row1, bool top_shared, bool bottom_shared, int b) {
    Flood f{z, g, flags, level, d8_offsets(g), {}, {}, {}, {}, row0, row1, labels};
    seed_band(f);
    f.next_label = band_first_label(b, g.cols);
    const int first = row0, last = row1 - 1;
    for (const int r : {first, last}) {
        if (!(r == first ? top_shared : bottom_shared)) continue;  // the grid's border: seeds already
        for (int c = 0; c < g.cols; ++c) {
            const std::size_t i = std::size_t(r) * g.cols + c;
            if (!g.valid[i] || flags[i]) continue;
            flags[i] = fill_closed | band_edge;
            labels[i] = Flood::unlabelled;  // labelled as it leaves the queue (label_edge)
            f.push_open(std::uint32_t(i));
        }
    }
    run(f);
    f.stats.labels = f.next_label - band_first_label(b, g.cols);
    return f.stats;
}

std::vector<float> water_levels(const Spills& spills, std::size_t labels) {
    // the label graph in compressed rows: each spill listed at both its labels
    std::vector<std::uint32_t> start(labels + 1, 0);
    for (const auto& [key, w] : spills) ++start[std::size_t(key >> 32) + 1], ++start[std::size_t(std::uint32_t(key)) + 1];
    for (std::size_t l = 0; l < labels; ++l) start[l + 1] += start[l];
    std::vector<std::pair<std::uint32_t, float>> next(start.back());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& [key, w] : spills) {
        const auto a = std::uint32_t(key >> 32), b = std::uint32_t(key);
        next[fill[a]++] = {b, w}, next[fill[b]++] = {a, w};
    }
    std::vector<float> level(labels, std::numeric_limits<float>::infinity());
    using Open = std::pair<float, std::uint32_t>;
    std::priority_queue<Open, std::vector<Open>, std::greater<>> open;
    level[0] = -std::numeric_limits<float>::infinity();
    open.push({level[0], 0});
    while (!open.empty()) {
        const auto [h, l] = open.top();
        open.pop();
        if (h > level[l]) continue;  // reached lower since
        for (std::uint32_t e = start[l]; e < start[l + 1]; ++e) {
            const auto [m, w] = next[e];
            if (const float hm = std::max(h, w); hm < level[m]) level[m] = hm, open.push({hm, m});
        }
    }
    return level;
}

}  // namespace penink::flood
