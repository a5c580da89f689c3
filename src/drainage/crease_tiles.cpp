#include "drainage/crease_tiles.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/common.hpp>

#include "core/error.hpp"
#include "core/hash64.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/fall_line_stems.hpp"
#include "drainage/line_tile_files.hpp"
#include "drainage/stem_reach.hpp"

namespace penink {

CreaseTileIndex crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                                  int tile, float z_top) {
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
    out.z_top = std::isnan(z_top) ? drape_height_top(g) : z_top;
    const StemParts& parts = out.parts;
    std::vector<glm::vec2> reach_lo(parts.sources.size()), reach_hi(parts.sources.size());
    out.stems.resize(parts.sources.size());
    for_each_stem_cells(g, dir, net, parts, [&](std::uint32_t s, const std::uint32_t* cells, std::uint32_t n) {
        boxes.plan_box(stem_cell_reach(cells, n, g, options), reach_lo[s], reach_hi[s]);
        out.stems[s] = stem_bound(reach_lo[s], reach_hi[s], stem_cell_travel(cells, n, g), parts.lo, parts.hi);
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
    : g_(g), dir_(dir), net_(net), side_(std::max(1, index.side)), parts_(std::move(index.parts)),
      bounds_(std::move(index.stems)), z_top_(index.z_top), store_(std::move(store)) {
    const auto side = std::uint32_t(side_);
    const std::uint32_t tx = (std::uint32_t(g.cols) + side - 1) / side, ty = (std::uint32_t(g.rows) + side - 1) / side;
    tiles_.resize(std::size_t(tx) * ty);
    if (index.lo.size() != tiles_.size() || index.hi.size() != tiles_.size())
        throw Error("drainage", "", "crease tile index of " + std::to_string(index.lo.size()) + " tiles for a grid of " +
                                        std::to_string(tiles_.size()),
                    ExitCode::internal);
    if (bounds_.size() != parts_.sources.size())
        throw Error("drainage", "", "crease tile index of " + std::to_string(bounds_.size()) + " stem bounds for " +
                                        std::to_string(parts_.sources.size()) + " stems",
                    ExitCode::internal);
    for (std::size_t k = 0; k < tiles_.size(); ++k) tiles_[k].lo = index.lo[k], tiles_[k].hi = index.hi[k];
    glm::vec2 blo, bhi;
    for (std::uint32_t s = 0; s < parts_.sources.size(); ++s) {
        const std::uint32_t c = parts_.sources[s] % std::uint32_t(g.cols), r = parts_.sources[s] / std::uint32_t(g.cols);
        Tile& t = tiles_[std::size_t(r / side) * tx + c / side];
        const int l = crease_tile_level(bounds_[s], g.dx);
        t.stems[std::size_t(l)].push_back(s);
        LevelBound& b = t.bound[std::size_t(l)];
        stem_bound_box(bounds_[s], parts_.lo, parts_.hi, blo, bhi);
        b.lo = glm::min(b.lo, blo), b.hi = glm::max(b.hi, bhi);
        b.most.plan = std::max(b.most.plan, bounds_[s].plan), b.most.rise = std::max(b.most.rise, bounds_[s].rise);
    }
}

CreaseTileIndex CreaseTiles::index() const {
    CreaseTileIndex out;
    out.side = side_;
    out.parts = parts_;
    out.stems = bounds_;
    out.z_top = z_top_;
    for (const Tile& t : tiles_) out.lo.push_back(t.lo), out.hi.push_back(t.hi);
    return out;
}

DemSurface& CreaseTiles::surface() {
    if (!surface_) {
        if (before_build_) std::exchange(before_build_, {})();
        surface_ = std::make_unique<DemSurface>(g_);
    }
    return *surface_;
}

namespace {

// Lines ids (ascending, all in `stems`, ascending, whose line i is from's line i) copied out of
// `from`, in that order.
std::unique_ptr<DrapedLineSet> lines_of(const std::vector<std::uint32_t>& ids, const std::vector<std::uint32_t>& stems,
                                        const DrapedLineSet& from) {
    auto out = std::make_unique<DrapedLineSet>();
    std::vector<std::uint32_t> at;  // line of `from` for each id
    at.reserve(ids.size());
    std::size_t n = 0, i = 0;
    for (std::uint32_t s : ids) {
        while (i < stems.size() && stems[i] < s) ++i;
        if (i == stems.size() || stems[i] != s)
            throw Error("drainage", "", "crease tile without stem " + std::to_string(s), ExitCode::internal);
        at.push_back(std::uint32_t(i)), n += from.lines[i].count;
    }
    out->vertices.resize(n);
    out->lines.reserve(ids.size());
    std::size_t first = 0;
    for (std::uint32_t line : at) {
        DrapedLine l = from.lines[line];
        std::copy_n(from.vertices.begin() + l.first, l.count, out->vertices.begin() + std::ptrdiff_t(first));
        l.first = std::uint32_t(first), first += l.count;
        out->lines.push_back(l);
    }
    return out;
}

// A crease part of `lines` lines built for `stems` stems: one a stem, else a builder's fault.
void check_part(std::size_t lines, std::size_t stems) {
    if (lines != stems)
        throw Error("drainage", "",
                    "crease part of " + std::to_string(lines) + " lines for " + std::to_string(stems) + " stems",
                    ExitCode::internal);
}

}  // namespace

void CreaseTiles::keep(const std::vector<std::uint32_t>& ids, std::unique_ptr<DrapedLineSet> lines, bool on_disk) {
    check_part(lines->lines.size(), ids.size());
    U32Map& map = on_disk ? query_ : kept_;
    auto& at = on_disk ? query_at_ : at_;
    for (std::uint32_t i = 0; i < ids.size(); ++i)
        map.insert(ids[i], std::uint32_t(at.size())), at.emplace_back(std::uint32_t(sets_.size()), i);
    stems_built_ += ids.size(), vertices_built_ += lines->vertices.size();
    sets_.push_back(std::move(lines));
}

std::uint64_t CreaseTiles::tile_key(std::size_t k, int l) const {
    const std::uint64_t fields[4] = {store_.key, std::uint64_t(side_), std::uint64_t(k), std::uint64_t(l)};
    return hash64(fields, sizeof fields);
}

std::string CreaseTiles::tile_path(std::size_t k, int l) const {
    return line_tile_path(store_.folder, std::uint32_t(k), l);
}

int crease_tile_level(const StemBound& b, double cell) {
    const double cells = double(stem_bound_plan(b)) / cell;
    int l = 0;
    for (double top = 4.0; l + 1 < crease_tile_levels && cells >= top; top *= 2.0) ++l;
    return l;
}

std::vector<CreaseTiles::Pick> CreaseTiles::picks_for_box(glm::vec2 lo, glm::vec2 hi, const LineTest& may_show) {
    const auto meets = [&](glm::vec2 a, glm::vec2 b) { return !(b.x < lo.x || a.x > hi.x || b.y < lo.y || a.y > hi.y); };
    std::vector<std::uint32_t> wanted, missing;
    // missing[cuts[k], cuts[k + 1]): level cut_level[k] of tile cut_tile[k]'s, ascending
    std::vector<std::size_t> cuts{0}, cut_tile;
    std::vector<int> cut_level;
    glm::vec2 blo, bhi;  // a stem's bound's box
    for (std::size_t k = 0; k < tiles_.size(); ++k) {
        const Tile& t = tiles_[k];
        if (!meets(t.lo, t.hi)) continue;
        for (int l = 0; l < crease_tile_levels; ++l) {
            const LevelBound& b = t.bound[std::size_t(l)];
            if (t.stems[std::size_t(l)].empty() || !meets(b.lo, b.hi) || (may_show && !may_show(b.most, b.lo, b.hi, z_top_)))
                continue;  // no stem of the level passes
            for (std::uint32_t s : t.stems[std::size_t(l)]) {
                stem_bound_box(bounds_[s], parts_.lo, parts_.hi, blo, bhi);
                if (!meets(blo, bhi) || (may_show && !may_show(bounds_[s], blo, bhi, z_top_))) continue;
                wanted.push_back(s);
                if (!kept_.find(s)) missing.push_back(s);
            }
            if (missing.size() > cuts.back())
                cuts.push_back(missing.size()), cut_tile.push_back(k), cut_level.push_back(l);
        }
    }
    std::sort(wanted.begin(), wanted.end());
    if (!missing.empty()) ++builds_;
    const auto ids_of = [&](std::size_t k) {
        return std::vector<std::uint32_t>(missing.begin() + std::ptrdiff_t(cuts[k]), missing.begin() + std::ptrdiff_t(cuts[k + 1]));
    };
    // the tiles' files first, read and decoded on all cores (a tile's lines whole while its
    // stems needed are copied out)
    std::vector<std::unique_ptr<DrapedLineSet>> read(cut_tile.size());
    if (!store_.folder.empty()) {
        std::atomic<std::size_t> count{0};
        parallel_chunks(cut_tile.size(), 1, [&](std::size_t k0, std::size_t k1) {
            for (std::size_t k = k0; k < k1; ++k) {
                DrapedLineSet whole;
                const std::vector<std::uint32_t>& stems = tiles_[cut_tile[k]].stems[cut_level[k]];
                if (read_line_tile(tile_path(cut_tile[k], cut_level[k]), tile_key(cut_tile[k], cut_level[k]), whole) &&
                    whole.lines.size() == stems.size())
                    read[k] = lines_of(ids_of(k), stems, whole), ++count;
            }
        });
        tiles_read_ += count;
    }
    // the others built, a tile at a time: its levels needed in one build on all cores (a part's
    // stems walk their trunks again: one build of a tile's levels costs less than one a level;
    // one build of many tiles' stems more than theirs one by one, larger working sets); with a
    // store, every stem of those levels, each level then coded and written on all cores
    const auto merged = [](std::vector<std::uint32_t> a, const std::vector<std::uint32_t>& b) {
        std::vector<std::uint32_t> out(a.size() + b.size());
        out.erase(std::merge(a.begin(), a.end(), b.begin(), b.end(), out.begin()), out.end());
        return out;
    };
    std::size_t to_build = 0, built = 0;  // tiles with cuts not read, for build_progress_
    for (std::size_t k = 0, last = std::size_t(-1); k < cut_tile.size(); ++k)
        if (!read[k] && cut_tile[k] != last) ++to_build, last = cut_tile[k];
    const auto tile_built = [&] {
        if (build_progress_) build_progress_(double(++built) / double(std::max<std::size_t>(to_build, 1)));
    };
    for (std::size_t k0 = 0, k1; k0 < cut_tile.size(); k0 = k1) {
        for (k1 = k0; k1 < cut_tile.size() && cut_tile[k1] == cut_tile[k0]; ++k1)
            if (read[k1]) keep(ids_of(k1), std::move(read[k1]), true);
        std::vector<std::size_t> todo;  // cuts of this tile still missing
        for (std::size_t k = k0; k < k1; ++k)
            if (!query_.find(missing[cuts[k]])) todo.push_back(k);
        if (todo.empty()) continue;
        const Tile& t = tiles_[cut_tile[k0]];
        if (!store_.folder.empty() && writable_) {
            std::vector<std::uint32_t> stems;
            for (std::size_t k : todo) stems = merged(std::move(stems), t.stems[cut_level[k]]);
            const DrapedLineSet whole = crease_part(g_, dir_, net_, surface(), parts_, stems);
            check_part(whole.lines.size(), stems.size());
            std::vector<std::uint8_t> written(todo.size(), 0);
            parallel_chunks(todo.size(), 1, [&](std::size_t j0, std::size_t j1) {
                for (std::size_t j = j0; j < j1; ++j) {
                    const std::size_t k = todo[j];
                    const std::unique_ptr<DrapedLineSet> level = lines_of(t.stems[cut_level[k]], stems, whole);
                    written[j] = write_line_tile(tile_path(cut_tile[k], cut_level[k]), tile_key(cut_tile[k], cut_level[k]),
                                                 *level);
                }
            });
            for (std::size_t j = 0; j < todo.size(); ++j) {
                ++tiles_built_;
                if (written[j]) ++tiles_written_;
                else writable_ = false;  // the tiles from now on built as needed, in memory only
                keep(ids_of(todo[j]), lines_of(ids_of(todo[j]), stems, whole), written[j] != 0);
            }
            tile_built();
            continue;
        }
        std::vector<std::uint32_t> need;
        for (std::size_t k : todo) need = merged(std::move(need), ids_of(k));
        keep(need, std::make_unique<DrapedLineSet>(crease_part(g_, dir_, net_, surface(), parts_, need)));
        tile_built();
    }
    std::vector<Pick> picks;
    picks.reserve(wanted.size());
    for (std::uint32_t s : wanted) {
        const std::uint32_t* i = kept_.find(s);
        const auto [set, line] = i ? at_[*i] : query_at_[*query_.find(s)];
        picks.push_back({s, sets_[set], line});
    }
    // the sets in files forgotten (the picks hold them while the caller uses them)
    for (const auto& [set, line] : query_at_) sets_[set].reset();
    query_ = U32Map(), query_at_.clear();
    return picks;
}

CreaseTiles::LineRefs CreaseTiles::line_refs_for_box(glm::vec2 lo, glm::vec2 hi, const LineTest& may_show) {
    const std::vector<Pick> picks = picks_for_box(lo, hi, may_show);
    LineRefs out;
    out.lines.reserve(picks.size()), out.vertices.reserve(picks.size());
    for (const Pick& p : picks) {
        const DrapedLine& l = p.set->lines[p.line];
        out.lines.push_back(l), out.vertices.push_back(p.set->vertices.data() + l.first);
        if (out.hold.empty() || out.hold.back() != p.set) out.hold.push_back(p.set);
    }
    return out;
}

DrapedLineSet CreaseTiles::lines_for_box(glm::vec2 lo, glm::vec2 hi, std::vector<std::uint32_t>* ids,
                                         const LineTest& may_show) {
    const std::vector<Pick> picks = picks_for_box(lo, hi, may_show);
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
