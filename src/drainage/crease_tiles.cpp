#include "drainage/crease_tiles.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include <glm/common.hpp>

#include "core/error.hpp"
#include "core/hash64.hpp"
#include "drainage/fall_line_stems.hpp"
#include "drainage/line_tile_files.hpp"
#include "drainage/stem_reach.hpp"

namespace penink {

CreaseTileIndex crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                                  int tile) {
    CreaseTileIndex out;
    out.side = std::max(1, tile);
    out.parts = stem_parts(g, dir, net);
    const auto side = std::uint32_t(out.side);
    const std::uint32_t tx = (std::uint32_t(g.cols) + side - 1) / side, ty = (std::uint32_t(g.rows) + side - 1) / side;
    out.lo.assign(std::size_t(tx) * ty, glm::vec2(std::numeric_limits<float>::infinity()));
    out.hi.assign(out.lo.size(), -out.lo[0]);
    const PlanBoxes boxes(g);
    const FallLineOptions options = fall_line_options(g);
    // each stem's reach on all cores, then joined into its tile's in stem order
    const StemParts& parts = out.parts;
    std::vector<glm::vec2> reach_lo(parts.sources.size()), reach_hi(parts.sources.size());
    for_each_stem_cells(g, dir, net, parts, [&](std::uint32_t s, const std::uint32_t* cells, std::uint32_t n) {
        boxes.plan_box(stem_cell_reach(cells, n, g, options), reach_lo[s], reach_hi[s]);
    });
    for (std::uint32_t s = 0; s < parts.sources.size(); ++s) {
        const std::uint32_t c = parts.sources[s] % std::uint32_t(g.cols), r = parts.sources[s] / std::uint32_t(g.cols);
        const std::size_t k = std::size_t(r / side) * tx + c / side;
        out.lo[k] = glm::min(out.lo[k], reach_lo[s]), out.hi[k] = glm::max(out.hi[k], reach_hi[s]);
    }
    return out;
}

CreaseTiles::CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net, int tile,
                         TileStore store)
    : CreaseTiles(g, dir, net, crease_tile_index(g, dir, net, tile), std::move(store)) {}

CreaseTiles::CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                         CreaseTileIndex index, TileStore store)
    : g_(g), dir_(dir), net_(net), side_(std::max(1, index.side)), store_(std::move(store)),
      parts_(std::move(index.parts)) {
    const auto side = std::uint32_t(side_);
    const std::uint32_t tx = (std::uint32_t(g.cols) + side - 1) / side, ty = (std::uint32_t(g.rows) + side - 1) / side;
    tiles_.resize(std::size_t(tx) * ty);
    if (index.lo.size() != tiles_.size() || index.hi.size() != tiles_.size())
        throw Error("drainage", "", "crease tile index of " + std::to_string(index.lo.size()) + " tiles for a grid of " +
                                        std::to_string(tiles_.size()),
                    ExitCode::internal);
    for (std::size_t k = 0; k < tiles_.size(); ++k) tiles_[k].lo = index.lo[k], tiles_[k].hi = index.hi[k];
    for (std::uint32_t s = 0; s < parts_.sources.size(); ++s) {
        const std::uint32_t c = parts_.sources[s] % std::uint32_t(g.cols), r = parts_.sources[s] / std::uint32_t(g.cols);
        tiles_[std::size_t(r / side) * tx + c / side].stems.push_back(s);
    }
}

CreaseTileIndex CreaseTiles::index() const {
    CreaseTileIndex out;
    out.side = side_;
    out.parts = parts_;
    for (const Tile& t : tiles_) out.lo.push_back(t.lo), out.hi.push_back(t.hi);
    return out;
}

std::size_t CreaseTiles::tiles_built() const {
    return std::size_t(std::count_if(tiles_.begin(), tiles_.end(), [](const Tile& t) { return t.lines != nullptr; }));
}

std::vector<CreaseTiles::Pick> CreaseTiles::picks_for_box(glm::vec2 lo, glm::vec2 hi) {
    std::vector<Pick> picks;
    for (std::size_t k = 0; k < tiles_.size(); ++k) {
        Tile& t = tiles_[k];
        if (t.stems.empty() || t.hi.x < lo.x || t.lo.x > hi.x || t.hi.y < lo.y || t.lo.y > hi.y) continue;
        if (!t.lines) {
            auto lines = std::make_unique<DrapedLineSet>();
            const std::uint64_t fields[3] = {store_.key, std::uint64_t(side_), std::uint64_t(k)};
            const std::uint64_t key = hash64(fields, sizeof fields);
            const std::string path = store_.folder.empty() ? std::string() : line_tile_path(store_.folder, std::uint32_t(k));
            std::vector<std::uint32_t> stems;
            if (!path.empty() && read_line_tile(path, key, stems, *lines) && stems == t.stems) {
                ++read_;
            } else {
                if (!surface_) {
                    if (before_build_) std::exchange(before_build_, {})();
                    surface_ = std::make_unique<DemSurface>(g_);
                }
                *lines = crease_part(g_, dir_, net_, *surface_, parts_, t.stems);
                if (!path.empty() && write_line_tile(path, key, t.stems, *lines)) ++written_;
            }
            t.lines = std::move(lines);
        }
        for (std::uint32_t i = 0; i < t.stems.size(); ++i) picks.push_back({t.stems[i], t.lines.get(), i});
    }
    std::sort(picks.begin(), picks.end(), [](const Pick& a, const Pick& b) { return a.stem < b.stem; });
    return picks;
}

CreaseTiles::LineRefs CreaseTiles::line_refs_for_box(glm::vec2 lo, glm::vec2 hi) {
    const std::vector<Pick> picks = picks_for_box(lo, hi);
    LineRefs out;
    out.lines.reserve(picks.size()), out.vertices.reserve(picks.size());
    for (const Pick& p : picks) {
        const DrapedLine& l = p.set->lines[p.line];
        out.lines.push_back(l), out.vertices.push_back(p.set->vertices.data() + l.first);
    }
    return out;
}

DrapedLineSet CreaseTiles::lines_for_box(glm::vec2 lo, glm::vec2 hi, std::vector<std::uint32_t>* ids) {
    const std::vector<Pick> picks = picks_for_box(lo, hi);
    DrapedLineSet out;
    std::size_t n = 0;
    for (const Pick& p : picks) n += p.set->lines[p.line].count;
    out.vertices.resize(n);
    out.lines.reserve(picks.size());
    if (ids) ids->clear();
    std::size_t at = 0;
    for (const Pick& p : picks) {
        DrapedLine l = p.set->lines[p.line];
        std::copy_n(p.set->vertices.begin() + l.first, l.count, out.vertices.begin() + std::ptrdiff_t(at));
        l.first = std::uint32_t(at), at += l.count;
        out.lines.push_back(l);
        if (ids) ids->push_back(p.stem);
    }
    index_lines(out);
    return out;
}

}  // namespace penink
