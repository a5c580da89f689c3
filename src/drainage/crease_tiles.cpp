#include "drainage/crease_tiles.hpp"

#include <algorithm>
#include <atomic>
#include <future>
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

namespace {

// Tile of the source cell `src` on a grid `cols` wide in tiles of `side`, `tx` tiles a row.
std::size_t tile_of(std::uint32_t src, std::uint32_t cols, std::uint32_t side, std::uint32_t tx) {
    return std::size_t(src / cols / side) * tx + src % cols / side;
}

// The units of a cols x rows grid of cells `cell` metres wide in tiles of `side`: `count` slots,
// tile after tile, each tile's levels in order; a stem's slot from its source cell and bound.
struct UnitSlots {
    std::uint32_t cols, side, tx;
    std::size_t count;
    double cell;
    UnitSlots(int tile, int grid_cols, int grid_rows, double cell_metres)
        : cols(std::uint32_t(grid_cols)), side(std::uint32_t(std::max(1, tile))), tx((cols + side - 1) / side),
          count(std::size_t(tx) * ((std::uint32_t(grid_rows) + side - 1) / side) * crease_tile_levels),
          cell(cell_metres) {}
    std::size_t of(std::uint32_t source, const StemBound& b) const {
        return tile_of(source, cols, side, tx) * crease_tile_levels + std::size_t(crease_tile_level(b, cell));
    }
};

// Stem bound b (on the stems' box [lo, hi]) counted into unit u's summary.
void add_to_unit(CreaseUnit& u, const StemBound& b, glm::vec2 lo, glm::vec2 hi) {
    glm::vec2 blo, bhi;
    stem_bound_box(b, lo, hi, blo, bhi);
    ++u.count, u.lo = glm::min(u.lo, blo), u.hi = glm::max(u.hi, bhi);
    u.most.plan = std::max(u.most.plan, b.plan), u.most.rise = std::max(u.most.rise, b.rise);
}

// A unit's stems `m` (ascending) coded into ids and bounds (bound_of(s): stem s's bound; `b`
// scratch).
template <class BoundOf>
void code_unit(const std::vector<std::uint32_t>& m, BoundOf&& bound_of, std::vector<StemBound>& b,
               std::vector<std::uint8_t>& ids, std::vector<std::uint8_t>& bounds) {
    b.clear();
    for (const std::uint32_t s : m) b.push_back(bound_of(s));
    ids = encode_stem_ids(m.data(), m.size()), bounds = encode_stem_bounds(b.data(), b.size());
}

// The index's parts, tile boxes and z_top into `ix` (side `tile`), and each row of tiles' stems'
// bounds: on_row(s0, s1, bounds, first_tile) for the stems [s0, s1) of each row with stems, in row
// order (stem s's bound bounds[s - s0]; first_tile: the row's first tile). The stems are in the
// order of their source cells, so a row's are consecutive: each row's are walked on all cores,
// each stem's reach joined into its tile's box by each chunk of stems, the chunks' boxes then
// joined (min and max: the boxes one pass in stem order gives).
template <class OnRow>
void index_rows(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net, int tile, float z_top,
                CreaseTileIndex& ix, OnRow&& on_row) {
    ix.side = std::max(1, tile);
    ix.parts = stem_parts(g, dir, net);
    const auto side = std::uint32_t(ix.side), cols = std::uint32_t(g.cols);
    const std::uint32_t tx = (cols + side - 1) / side, ty = (std::uint32_t(g.rows) + side - 1) / side;
    ix.lo.assign(std::size_t(tx) * ty, glm::vec2(std::numeric_limits<float>::infinity()));
    ix.hi.assign(ix.lo.size(), -ix.lo[0]);
    const PlanBoxes boxes(g);
    const FallLineOptions options = fall_line_options(g);
    ix.z_top = std::isnan(z_top) ? drape_height_top(g) : z_top;
    const StemParts& parts = ix.parts;
    // the rows with stems: their first stems (and the end), their first tiles
    std::vector<std::size_t> cuts{0}, first_tiles;
    for (std::uint32_t row = 0; row < ty; ++row) {
        const std::uint64_t end_cell = std::uint64_t(std::min(std::uint32_t(g.rows), (row + 1) * side)) * cols;
        const auto s1 = std::size_t(std::lower_bound(parts.sources.begin() + std::ptrdiff_t(cuts.back()), parts.sources.end(), end_cell) -
                                    parts.sources.begin());
        if (s1 > cuts.back()) cuts.push_back(s1), first_tiles.push_back(std::size_t(row) * tx);
    }
    std::vector<StemBound> bounds;  // the row's stems'
    std::vector<std::vector<glm::vec2>> chunk_lo(stem_chunks_most), chunk_hi(stem_chunks_most);  // the row's tiles'
    std::size_t s0 = 0, first_tile = 0;
    const auto start = [&](std::size_t k) {
        s0 = cuts[k], first_tile = first_tiles[k];
        bounds.assign(cuts[k + 1] - s0, StemBound{});
        for (std::size_t c = 0; c < stem_chunks_most; ++c) chunk_lo[c].clear(), chunk_hi[c].clear();
    };
    if (cuts.size() < 2) return;
    start(0);
    for_each_stem_cells(
        g, dir, net, parts,
        [&](std::size_t c, std::uint32_t s, const std::uint32_t* cells, const glm::vec2* xy, std::uint32_t n) {
            glm::vec2 lo, hi;
            boxes.plan_box(stem_cell_reach(cells, n, g, options), lo, hi);
            bounds[s - s0] = stem_bound(lo, hi, stem_cell_travel(cells, n, g, xy), parts.lo, parts.hi);
            if (chunk_lo[c].empty())  // this chunk's thread alone
                chunk_lo[c].assign(tx, glm::vec2(std::numeric_limits<float>::infinity())), chunk_hi[c].assign(tx, -chunk_lo[c][0]);
            const std::size_t k = tile_of(parts.sources[s], cols, side, tx) - first_tile;
            chunk_lo[c][k] = glm::min(chunk_lo[c][k], lo), chunk_hi[c][k] = glm::max(chunk_hi[c][k], hi);
        },
        cuts,
        [&](std::size_t k) {
            for (std::size_t c = 0; c < stem_chunks_most; ++c)
                for (std::size_t j = 0; j < chunk_lo[c].size(); ++j)
                    ix.lo[first_tile + j] = glm::min(ix.lo[first_tile + j], chunk_lo[c][j]),
                                       ix.hi[first_tile + j] = glm::max(ix.hi[first_tile + j], chunk_hi[c][j]);
            on_row(s0, cuts[k + 1], bounds, first_tile);
            if (k + 2 < cuts.size()) start(k + 1);
        });
}

}  // namespace

CreaseTileIndex crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                                  int tile, float z_top) {
    CreaseTileIndex out;
    index_rows(g, dir, net, tile, z_top, out,
               [&](std::size_t s0, std::size_t s1, const std::vector<StemBound>& bounds, std::size_t) {
                   if (out.stems.empty()) out.stems.resize(out.parts.sources.size());
                   std::copy(bounds.begin(), bounds.begin() + std::ptrdiff_t(s1 - s0), out.stems.begin() + std::ptrdiff_t(s0));
               });
    out.units = crease_units(out, g.cols, g.rows, g.dx);
    return out;
}

std::vector<CreaseUnit> crease_units(const CreaseTileIndex& index, int cols, int rows, double cell) {
    const UnitSlots slot(index.side, cols, rows, cell);
    const std::size_t n = std::min(index.parts.sources.size(), index.stems.size()), slots = slot.count;
    // each chunk of stems into a table of its own, joined after (min, max and sums: any order gives
    // the same units)
    const std::size_t per = chunk_length(n, 1 << 16);
    std::vector<std::vector<CreaseUnit>> parts((n + per - 1) / per);
    parallel_chunks(n, 1 << 16, [&](std::size_t s0, std::size_t s1) {
        std::vector<CreaseUnit>& t = parts[s0 / per];
        t.resize(slots);
        for (std::size_t s = s0; s < s1; ++s) {
            const StemBound& b = index.stems[s];
            add_to_unit(t[slot.of(index.parts.sources[s], b)], b, index.parts.lo, index.parts.hi);
        }
    });
    std::vector<CreaseUnit> out;
    for (std::size_t i = 0; i < slots; ++i) {
        CreaseUnit u;
        for (const std::vector<CreaseUnit>& t : parts) {
            const CreaseUnit& v = t[i];
            u.count += v.count, u.lo = glm::min(u.lo, v.lo), u.hi = glm::max(u.hi, v.hi);
            u.most.plan = std::max(u.most.plan, v.most.plan), u.most.rise = std::max(u.most.rise, v.most.rise);
        }
        if (!u.count) continue;
        u.tile = std::uint32_t(i / crease_tile_levels), u.level = std::uint32_t(i % crease_tile_levels);
        out.push_back(u);
    }
    return out;
}

CodedCreaseIndex code_crease_index(CreaseTileIndex index, int cols, int rows, double cell) {
    CodedCreaseIndex out;
    const std::vector<std::vector<std::uint32_t>> members = crease_unit_stems(index, cols, rows, cell);
    out.ids.resize(members.size()), out.bounds.resize(members.size());
    parallel_chunks(members.size(), 1, [&](std::size_t u0, std::size_t u1) {
        std::vector<StemBound> b;
        for (std::size_t u = u0; u < u1; ++u)
            code_unit(members[u], [&](std::uint32_t s) { return index.stems[s]; }, b, out.ids[u], out.bounds[u]);
    });
    index.stems = {};
    out.index = std::move(index);
    return out;
}

CodedCreaseIndex coded_crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                         const FlowNetwork& net, int tile, float z_top) {
    CodedCreaseIndex out;
    CreaseTileIndex& ix = out.index;
    const UnitSlots slot(std::max(1, tile), g.cols, g.rows, g.dx);
    std::vector<std::vector<std::uint32_t>> members(std::size_t(slot.tx) * crease_tile_levels);  // a row's units' stems
    std::vector<std::uint32_t> used;  // their slots with stems, ascending
    index_rows(g, dir, net, tile, z_top, ix, [&](std::size_t s0, std::size_t s1, const std::vector<StemBound>& bounds,
                                                 std::size_t first_tile) {
        // the row's units (crease_units' summaries, in tile then level order) and their stems, in stem order
        const std::size_t first_slot = first_tile * crease_tile_levels;
        used.clear();
        for (std::size_t s = s0; s < s1; ++s) {
            const std::size_t k = slot.of(ix.parts.sources[s], bounds[s - s0]) - first_slot;
            if (members[k].empty()) used.push_back(std::uint32_t(k));
            members[k].push_back(std::uint32_t(s));
        }
        std::sort(used.begin(), used.end());
        const std::size_t u_first = ix.units.size();
        for (const std::uint32_t k : used) {
            CreaseUnit u;
            u.tile = std::uint32_t((first_slot + k) / crease_tile_levels), u.level = std::uint32_t((first_slot + k) % crease_tile_levels);
            for (const std::uint32_t s : members[k]) add_to_unit(u, bounds[s - s0], ix.parts.lo, ix.parts.hi);
            ix.units.push_back(u);
        }
        out.ids.resize(ix.units.size()), out.bounds.resize(ix.units.size());
        parallel_chunks(used.size(), 1, [&](std::size_t j0, std::size_t j1) {
            std::vector<StemBound> b;
            for (std::size_t j = j0; j < j1; ++j)
                code_unit(members[used[j]], [&](std::uint32_t s) { return bounds[s - s0]; }, b, out.ids[u_first + j],
                          out.bounds[u_first + j]);
        });
        for (const std::uint32_t k : used) members[k] = {};
    });
    return out;
}

CreaseTiles::CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net, int tile,
                         TileStore store)
    : CreaseTiles(g, dir, net, crease_tile_index(g, dir, net, tile), std::move(store)) {}

std::vector<std::vector<std::uint32_t>> crease_unit_stems(const CreaseTileIndex& index, int cols, int rows, double cell) {
    const UnitSlots slot(index.side, cols, rows, cell);
    const auto fault = [] {
        throw Error("drainage", "", "crease tile index whose stems do not fit its units", ExitCode::internal);
    };
    std::vector<std::uint32_t> slot_unit(slot.count, ~0u);  // tile x level -> unit
    for (std::size_t i = 0; i < index.units.size(); ++i) {
        const CreaseUnit& u = index.units[i];
        const std::size_t at = std::size_t(u.tile) * crease_tile_levels + u.level;
        if (u.level >= std::uint32_t(crease_tile_levels) || at >= slot.count || slot_unit[at] != ~0u) fault();
        slot_unit[at] = std::uint32_t(i);
    }
    std::vector<std::vector<std::uint32_t>> out(index.units.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i].reserve(index.units[i].count);
    if (index.stems.size() != index.parts.sources.size()) fault();
    for (std::uint32_t s = 0; s < index.parts.sources.size(); ++s) {
        const std::uint32_t u = slot_unit[slot.of(index.parts.sources[s], index.stems[s])];
        if (u == ~0u || out[u].size() == index.units[u].count) fault();
        out[u].push_back(s);
    }
    for (std::size_t i = 0; i < out.size(); ++i)
        if (out[i].size() != index.units[i].count) fault();
    return out;
}

CreaseTiles::CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                         CreaseTileIndex index, TileStore store, CreaseIndexReader reader)
    : g_(g), dir_(dir), net_(net), side_(std::max(1, index.side)), z_top_(index.z_top), reader_(std::move(reader)),
      store_(std::move(store)) {
    const auto side = std::uint32_t(side_);
    const std::uint32_t tx = (std::uint32_t(g.cols) + side - 1) / side, ty = (std::uint32_t(g.rows) + side - 1) / side;
    tiles_.resize(std::size_t(tx) * ty), tiles_across_ = std::max<std::size_t>(tx, 1);
    const auto fault = [](const std::string& what) { throw Error("drainage", "", "crease tile index " + what, ExitCode::internal); };
    if (index.lo.size() != tiles_.size() || index.hi.size() != tiles_.size())
        fault("of " + std::to_string(index.lo.size()) + " tiles for a grid of " + std::to_string(tiles_.size()));
    for (std::size_t k = 0; k < tiles_.size(); ++k) tiles_[k].lo = index.lo[k], tiles_[k].hi = index.hi[k];
    parts_.lo = index.parts.lo, parts_.hi = index.parts.hi;
    const bool whole = !index.stems.empty() || !reader_.whole || !reader_.unit;
    if (whole && index.units.empty()) index.units = crease_units(index, g.cols, g.rows, g.dx);
    for (std::size_t i = 0; i < index.units.size(); ++i) {
        const CreaseUnit& u = index.units[i];
        if (u.tile >= tiles_.size() || u.level >= std::uint32_t(crease_tile_levels) || u.count == 0 ||
            (i && std::pair(u.tile, u.level) <= std::pair(index.units[i - 1].tile, index.units[i - 1].level)))
            fault("with a unit out of order or range");
        tiles_[u.tile].unit[u.level] = u, tiles_[u.tile].at[u.level] = std::uint32_t(i), stem_count_ += u.count;
    }
    if (whole) take_index(std::move(index));
}

void CreaseTiles::take_index(CreaseTileIndex index) {
    if (index.parts.lo != parts_.lo || index.parts.hi != parts_.hi)
        throw Error("drainage", "", "crease tile index of another box", ExitCode::internal);
    index.units.clear();  // this one's, in order
    for (const Tile& t : tiles_)
        for (const CreaseUnit& u : t.unit)
            if (u.count) index.units.push_back(u);
    std::vector<std::vector<std::uint32_t>> stems = crease_unit_stems(index, g_.cols, g_.rows, g_.dx);
    for (std::size_t i = 0; i < stems.size(); ++i)
        tiles_[index.units[i].tile].stems[index.units[i].level] = std::move(stems[i]);
    parts_ = std::move(index.parts), bounds_ = std::move(index.stems);
    loaded_ = true;
}

void CreaseTiles::load_index() {
    if (!loaded_) take_index(reader_.whole());
}

CreaseTileIndex CreaseTiles::index() {
    load_index();
    CreaseTileIndex out;
    out.side = side_;
    out.parts = parts_;
    out.stems = bounds_;
    out.z_top = z_top_;
    for (const Tile& t : tiles_) {
        out.lo.push_back(t.lo), out.hi.push_back(t.hi);
        for (const CreaseUnit& u : t.unit)
            if (u.count) out.units.push_back(u);
    }
    return out;
}

DemSurface& CreaseTiles::surface() {
    if (!surface_) {
        if (before_build_) std::exchange(before_build_, {})();
        surface_ = std::make_unique<DemSurface>(g_, DemSurface::Normals::on_demand);
    }
    return *surface_;
}

namespace {

// Lines at[0], at[1], ... of `from` copied out, in that order.
std::unique_ptr<DrapedLineSet> lines_at(const std::vector<std::uint32_t>& at, const DrapedLineSet& from) {
    auto out = std::make_unique<DrapedLineSet>();
    std::size_t n = 0;
    for (std::uint32_t line : at) n += from.lines[line].count;
    out->vertices.resize(n);
    out->lines.reserve(at.size());
    std::size_t first = 0;
    for (std::uint32_t line : at) {
        DrapedLine l = from.lines[line];
        std::copy_n(from.vertices.begin() + l.first, l.count, out->vertices.begin() + std::ptrdiff_t(first));
        l.first = std::uint32_t(first), first += l.count;
        out->lines.push_back(l);
    }
    return out;
}

// Lines ids (ascending, all in `stems`, ascending, whose line i is from's line i) copied out of
// `from`, in that order.
std::unique_ptr<DrapedLineSet> lines_of(const std::vector<std::uint32_t>& ids, const std::vector<std::uint32_t>& stems,
                                        const DrapedLineSet& from) {
    std::vector<std::uint32_t> at;  // line of `from` for each id
    at.reserve(ids.size());
    std::size_t i = 0;
    for (std::uint32_t s : ids) {
        while (i < stems.size() && stems[i] < s) ++i;
        if (i == stems.size() || stems[i] != s)
            throw Error("drainage", "", "crease tile without stem " + std::to_string(s), ExitCode::internal);
        at.push_back(std::uint32_t(i));
    }
    return lines_at(at, from);
}

// A crease part of `lines` lines built for `stems` stems: one a stem, else a builder's fault.
void check_part(std::size_t lines, std::size_t stems) {
    if (lines != stems)
        throw Error("drainage", "",
                    "crease part of " + std::to_string(lines) + " lines for " + std::to_string(stems) + " stems",
                    ExitCode::internal);
}

}  // namespace

void CreaseTiles::keep(const std::vector<std::uint32_t>& ids, std::unique_ptr<DrapedLineSet> lines, bool on_disk,
                       int detail) {
    check_part(lines->lines.size(), ids.size());
    if (ids.empty()) return;  // (a set of no stem would never be let go)
    U32Map& map = on_disk ? query_ : kept_;
    auto& at = on_disk ? query_at_ : at_;
    for (std::uint32_t i = 0; i < ids.size(); ++i)
        map.insert(ids[i], std::uint32_t(at.size())), at.emplace_back(std::uint32_t(sets_.size()), i);
    stems_built_ += ids.size(), vertices_built_ += lines->vertices.size();
    sets_.push_back(std::move(lines)), set_detail_.push_back(std::uint8_t(detail));
}

std::uint64_t CreaseTiles::tile_key(std::size_t k, int l, int d) const {
    const std::uint64_t fields[5] = {store_.key, std::uint64_t(side_), std::uint64_t(k), std::uint64_t(l), std::uint64_t(d)};
    return hash64(fields, d > 0 ? sizeof fields : 4 * sizeof(std::uint64_t));
}

std::string CreaseTiles::tile_path(std::size_t k, int l, int d) const {
    return line_tile_path(store_.folder, std::uint32_t(k), l, d);
}

double CreaseTiles::detail_spacing(int d) const { return std::ldexp(g_.dx, d); }

int CreaseTiles::unit_detail(const CreaseUnit& u, const LineDetail& detail) const {
    if (!detail) return 0;
    const double allowed = detail(u.lo, u.hi, z_top_);
    int d = 0;
    while (d < crease_detail_levels && detail_spacing(d + 1) <= allowed) ++d;
    return d;
}

int CreaseTiles::read_unit(std::size_t k, int l, int d, TileLines& out, const TileNeed& need, const TileNeed& enough) const {
    const bool copy = d >= crease_copy_detail;
    // a copy of some of the unit's stems (written by a query that needed those alone) is read
    // alone where it holds what the query needs, else gives way to a file of more of them at
    // detail 0, thinned
    TileLines some;
    bool some_read = false;
    if (copy && read_line_tile(tile_path(k, l, d), tile_key(k, l, d), out, need)) {
        if (out.stems.size() == tiles_[k].unit[std::size_t(l)].count || (enough && enough(out))) return 1;
        some = std::move(out), some_read = true, out = {};
    }
    if (!read_line_tile(tile_path(k, l), tile_key(k, l), out, need) || (some_read && out.stems.size() <= some.stems.size())) {
        if (!some_read) return 0;
        out = std::move(some);
        if (need) need(out);  // (what the caller found in the file it is given)
        return 1;
    }
    if (d == 0 || out.lines.lines.size() != out.stems.size()) return 1;  // (no line needed: none decoded)
    out.lines = thinned_lines(out.lines, detail_spacing(d));  // a copy made, kept for the next query
    return copy && writable_ &&
                   write_line_tile(tile_path(k, l, d), tile_key(k, l, d), crease_lattice(g_), out.lines, out.stems, out.bounds, out.rest)
               ? 2
               : 1;
}

DrapedLineSet thinned_lines(const DrapedLineSet& from, double spacing) {
    DrapedLineSet out;
    out.lines.reserve(from.lines.size());
    const double s2 = spacing * spacing;
    for (const DrapedLine& l : from.lines) {
        DrapedLine t = l;
        t.first = std::uint32_t(out.vertices.size());
        const DrapedVertex* v = from.vertices.data() + l.first;
        std::uint32_t last = 0;  // the last vertex kept
        out.vertices.push_back(v[0]);
        for (std::uint32_t i = 1; i + 1 < l.count; ++i) {
            const double dx = double(v[i].x) - v[last].x, dy = double(v[i].y) - v[last].y, dz = double(v[i].z) - v[last].z;
            if (dx * dx + dy * dy + dz * dz >= s2) out.vertices.push_back(v[i]), last = i;
        }
        if (l.count > 1) out.vertices.push_back(v[l.count - 1]);
        t.count = std::uint32_t(out.vertices.size()) - t.first;
        out.lines.push_back(t);
    }
    index_lines(out);
    return out;
}

StemBound crease_line_bound(const DrapedLineSet& lines, std::size_t i, const StemBound& reach, glm::vec2 lo, glm::vec2 hi) {
    const DrapedLine& l = lines.lines[i];
    const DrapedVertex* v = lines.vertices.data() + l.first;
    glm::vec2 box_lo(std::numeric_limits<float>::infinity()), box_hi(-std::numeric_limits<float>::infinity());
    StemTravel t;
    for (std::uint32_t k = 0; k < l.count; ++k) {
        box_lo = glm::min(box_lo, glm::vec2(v[k].x, v[k].y)), box_hi = glm::max(box_hi, glm::vec2(v[k].x, v[k].y));
        if (k > 0)
            t.plan += std::hypot(double(v[k].x) - double(v[k - 1].x), double(v[k].y) - double(v[k - 1].y)),
                t.rise += std::abs(double(v[k].z) - double(v[k - 1].z));
    }
    return stem_line_bound(box_lo, box_hi, t, reach, lo, hi);
}

int crease_tile_level(const StemBound& b, double cell) {
    const double cells = double(stem_bound_plan(b)) / cell;
    int l = 0;
    for (double top = 4.0; l + 1 < crease_tile_levels && cells >= top; top *= 2.0) ++l;
    return l;
}

std::vector<CreaseTiles::Pick> CreaseTiles::picks_for_box(glm::vec2 lo, glm::vec2 hi, const LineTest& may_show,
                                                          const LineDetail& detail, std::size_t row) {
    const auto meets = [&](glm::vec2 a, glm::vec2 b) { return !(b.x < lo.x || a.x > hi.x || b.y < lo.y || a.y > hi.y); };
    const auto passes = [&](const StemBound& b, glm::vec2 blo, glm::vec2 bhi) {
        return meets(blo, bhi) && (!may_show || may_show(b, blo, bhi, z_top_));
    };
    const auto bound_passes = [&](const StemBound& b) {  // (the box its own)
        glm::vec2 box_lo, box_hi;
        stem_bound_box(b, parts_.lo, parts_.hi, box_lo, box_hi);
        return passes(b, box_lo, box_hi);
    };
    // whether a file of stems `held` (ascending) holds every one of `stems` (ascending; bounds
    // `bounds`, the index's) whose bound passes: a file of some of a unit's stems then gives the
    // query what its whole file would (a stem whose index bound fails has a line whose bound fails)
    const auto holds_passing = [&](const std::vector<std::uint32_t>& held, const std::vector<std::uint32_t>& stems,
                                   const std::vector<StemBound>& bounds) {
        std::size_t h = 0;
        for (std::size_t i = 0; i < stems.size(); ++i) {
            if (!bound_passes(bounds[i])) continue;
            while (h < held.size() && held[h] < stems[i]) ++h;
            if (h == held.size() || held[h] != stems[i]) return false;
        }
        return true;
    };
    // the units whose summary passes (the others have no stem that does), and their detail
    std::vector<std::pair<std::size_t, int>> units;
    std::vector<int> unit_d;
    for (std::size_t k = 0; k < tiles_.size(); ++k) {
        const Tile& t = tiles_[k];
        if (!meets(t.lo, t.hi) || (row != all_rows && k / tiles_across_ != row)) continue;
        for (int l = 0; l < crease_tile_levels; ++l) {
            const CreaseUnit& u = t.unit[std::size_t(l)];
            if (u.count && passes(u.most, u.lo, u.hi)) units.emplace_back(k, l), unit_d.push_back(unit_detail(u, detail));
        }
    }
    // stems, the detail they are given at, and the bound they passed by: the index's where they
    // were not read from a file (their line's, crease_line_bound, then tested too), else the file's
    // (already their line's)
    struct Wanted {
        std::uint32_t stem;
        int d;
        StemBound bound;
        bool operator<(const Wanted& o) const { return stem < o.stem || (stem == o.stem && d < o.d); }
    };
    std::vector<Wanted> wanted;
    std::vector<std::uint32_t> dropped;  // stems built and written whose line's bound fails
    std::size_t copies = 0;                              // copies written
    // done: read from its file, its stems tested by the bounds there; or without a sound file, no
    // stem of it passing (its stems' bounds read from the index's unit alone)
    std::vector<std::uint8_t> done(units.size(), 0);
    bool touched = false;  // stems read or built
    // the stems of each unit not done and their bounds, as its block in the index gives them
    // (without the whole index loaded)
    std::vector<std::vector<std::uint32_t>> unit_ids(units.size());
    std::vector<std::vector<StemBound>> unit_bounds(units.size());
    if (!loaded_ && !store_.folder.empty()) {
        std::vector<std::unique_ptr<DrapedLineSet>> got(units.size());
        std::vector<std::vector<std::uint32_t>> ids(units.size());
        std::atomic<std::size_t> written{0};
        parallel_chunks(units.size(), 1, [&](std::size_t u0, std::size_t u1) {
            for (std::size_t u = u0; u < u1; ++u) {
                const auto [k, l] = units[u];
                TileLines whole;
                std::vector<std::uint32_t> at;  // the lines whose bounds pass
                const auto passing = [&](const TileLines& t) {
                    at.clear(), ids[u].clear();
                    for (std::uint32_t i = 0; i < t.stems.size(); ++i)
                        if (bound_passes(t.bounds[i])) at.push_back(i), ids[u].push_back(t.stems[i]);
                    return !at.empty();
                };
                // a file of some of its stems is enough when it holds all that pass
                const auto holds_all_passing = [&](const TileLines& t) {
                    const TileRest& rest = t.rest;
                    return rest.stems.size() + t.stems.size() == tiles_[k].unit[std::size_t(l)].count &&
                           std::none_of(rest.bounds.begin(), rest.bounds.end(), bound_passes);  // none it leaves out passes
                };
                const int how = read_unit(k, l, unit_d[u], whole, passing, holds_all_passing);
                written += how == 2;
                bool read = how > 0 && whole.stems.size() == tiles_[k].unit[std::size_t(l)].count;
                TileLines index;  // the unit's stems and bounds as the index gives them
                if (how > 0 && !read) {
                    const TileRest& rest = whole.rest;
                    if (rest.stems.size() + whole.stems.size() == tiles_[k].unit[std::size_t(l)].count) {
                        read = holds_all_passing(whole);
                    } else {
                        reader_.unit(tiles_[k].at[std::size_t(l)], index.stems, index.bounds);
                        read = holds_passing(whole.stems, index.stems, index.bounds);
                    }
                }
                if (!read) {
                    if (index.stems.empty()) reader_.unit(tiles_[k].at[std::size_t(l)], index.stems, index.bounds);
                    whole.stems = std::move(index.stems), whole.bounds = std::move(index.bounds), passing(whole);
                }
                if (read) got[u] = lines_at(at, whole.lines);
                else if (at.empty()) done[u] = 1;  // nothing of it needed
                else unit_ids[u] = std::move(whole.stems), unit_bounds[u] = std::move(whole.bounds);
            }
        });
        copies += written;
        for (std::size_t u = 0; u < units.size(); ++u) {
            if (!got[u]) continue;
            done[u] = 1, touched = true, ++tiles_read_;
            for (std::uint32_t s : ids[u]) wanted.push_back({s, unit_d[u], {}});
            if (!ids[u].empty()) keep(ids[u], std::move(got[u]), true, unit_d[u]);
        }
    }
    // the units not done: their stems from their blocks (above), else from the whole index
    // (loaded now when there is no reader of the stems' sources: building needs them)
    const bool not_done = std::find(done.begin(), done.end(), 0) != done.end();
    if (not_done && !loaded_ && (store_.folder.empty() || !reader_.sources)) load_index();
    const auto stems_of = [&](std::size_t u) -> const std::vector<std::uint32_t>& {
        return loaded_ ? tiles_[units[u].first].stems[std::size_t(units[u].second)] : unit_ids[u];
    };
    const auto bound_of = [&](std::size_t u, std::size_t i) -> const StemBound& {
        return loaded_ ? bounds_[stems_of(u)[i]] : unit_bounds[u][i];
    };
    std::vector<std::uint32_t> missing;
    // missing[cuts[k], cuts[k + 1]): level cut_level[k] of tile cut_tile[k]'s (unit cut_unit[k]), ascending
    std::vector<std::size_t> cuts{0}, cut_tile, cut_unit;
    std::vector<int> cut_level, cut_d;
    // the stems a cut's unit is built and written with: all of them, or where the query needs few
    // (crease_partial_share) those it needs alone (cut_some[k]: ids ascending and their bounds)
    std::vector<std::unique_ptr<TileLines>> cut_some;
    glm::vec2 blo, bhi;  // a stem's bound's box
    for (std::size_t u = 0; u < units.size(); ++u) {
        if (done[u]) continue;
        const auto [k, l] = units[u];
        const std::vector<std::uint32_t>& ids = stems_of(u);
        auto some = std::make_unique<TileLines>();
        double plan_all = 0.0, plan_some = 0.0;  // the unit's and the needed stems' plan bounds
        TileRest rest;                           // the stems not needed
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const std::uint32_t s = ids[i];
            const double plan = double(stem_bound_plan(bound_of(u, i)));
            plan_all += plan;
            stem_bound_box(bound_of(u, i), parts_.lo, parts_.hi, blo, bhi);
            if (!passes(bound_of(u, i), blo, bhi)) {
                rest.stems.push_back(s), rest.bounds.push_back(bound_of(u, i));
                continue;
            }
            wanted.push_back({s, unit_d[u], bound_of(u, i)});
            some->stems.push_back(s), some->bounds.push_back(bound_of(u, i)), plan_some += plan;
            if (!kept_.find(s)) missing.push_back(s);
        }
        if (missing.size() > cuts.back()) {
            cuts.push_back(missing.size()), cut_tile.push_back(k), cut_level.push_back(l), cut_d.push_back(unit_d[u]),
                cut_unit.push_back(u);
            if (plan_some > crease_partial_share * plan_all) some.reset();
            else some->rest = std::move(rest);
            cut_some.push_back(std::move(some));
        }
    }
    const auto file_ids = [&](std::size_t k) -> const std::vector<std::uint32_t>& {  // cut k's unit's stems built
        return cut_some[k] ? cut_some[k]->stems : stems_of(cut_unit[k]);
    };
    const auto file_bound = [&](std::size_t k, std::size_t i) -> const StemBound& {  // and their bounds
        return cut_some[k] ? cut_some[k]->bounds[i] : bound_of(cut_unit[k], i);
    };
    std::sort(wanted.begin(), wanted.end());
    built_in_query_ = built_in_query_ || touched || !missing.empty();
    const auto ids_of = [&](std::size_t k) {
        return std::vector<std::uint32_t>(missing.begin() + std::ptrdiff_t(cuts[k]), missing.begin() + std::ptrdiff_t(cuts[k + 1]));
    };
    // the tiles' files first, read and decoded on all cores (a tile's lines whole while its
    // stems needed are copied out)
    // (the stems needed whose line's bound, in the file, passes; those failing in read_dropped)
    std::vector<std::unique_ptr<DrapedLineSet>> read(cut_tile.size());
    std::vector<std::vector<std::uint32_t>> read_ids(cut_tile.size()), read_dropped(cut_tile.size());
    if (!store_.folder.empty()) {
        std::atomic<std::size_t> count{0}, written{0};
        parallel_chunks(cut_tile.size(), 1, [&](std::size_t k0, std::size_t k1) {
            for (std::size_t k = k0; k < k1; ++k) {
                TileLines whole;
                const auto holds_missing = [&](const TileLines& t) {
                    return std::includes(t.stems.begin(), t.stems.end(), missing.begin() + std::ptrdiff_t(cuts[k]),
                                         missing.begin() + std::ptrdiff_t(cuts[k + 1]));
                };
                const int how = read_unit(cut_tile[k], cut_level[k], cut_d[k], whole, {}, holds_missing);
                written += how == 2;
                if (how > 0 && holds_missing(whole)) {
                    for (std::size_t i = 0, n = cuts[k]; i < whole.stems.size() && n < cuts[k + 1]; ++i) {
                        if (whole.stems[i] != missing[n]) continue;
                        (bound_passes(whole.bounds[i]) ? read_ids[k] : read_dropped[k]).push_back(missing[n++]);
                    }
                    if (read_ids[k].size() == whole.stems.size()) {  // every stem needed: the lines as read
                        read[k] = std::make_unique<DrapedLineSet>(std::move(whole.lines));
                        read[k]->index = {};  // (as lines_of leaves it)
                    } else {
                        read[k] = lines_of(read_ids[k], whole.stems, whole.lines);
                    }
                    ++count;
                }
            }
        });
        tiles_read_ += count, copies += written;
        for (const std::vector<std::uint32_t>& d : read_dropped) dropped.insert(dropped.end(), d.begin(), d.end());
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
    const auto missing_in = [&](const std::vector<std::size_t>& todo) {  // the stems missing from these cuts
        std::vector<std::uint32_t> need;
        for (std::size_t k : todo) need = merged(std::move(need), ids_of(k));
        return need;
    };
    std::size_t to_build = 0, built = 0;  // tiles with cuts not read, for build_progress_
    for (std::size_t k = 0, last = std::size_t(-1); k < cut_tile.size(); ++k)
        if (!read[k] && cut_tile[k] != last) ++to_build, last = cut_tile[k];
    const auto tile_built = [&] {  // (a row of a query by rows: its share of the whole)
        const double f = double(++built) / double(std::max<std::size_t>(to_build, 1));
        if (build_progress_) build_progress_(progress_shown_ = progress_from_ + progress_share_ * f);
    };
    // a tile's files are written beside the next tile's build (one tile's writes at a time, in
    // tile order), and its stems kept once they are: the same sets kept in the same order
    struct TileWrites {
        std::vector<std::size_t> todo;  // its cuts
        std::vector<std::uint8_t> written;
        // the stems the query needs, at its detail where their file is written (forgotten after
        // the query: never a finer one asked of them; those whose line's bound fails left out,
        // in dropped), else whole (kept in memory)
        std::vector<std::unique_ptr<DrapedLineSet>> needed;
        std::vector<std::vector<std::uint32_t>> needed_ids, dropped;
    };
    const auto write_tile = [&](TileWrites& w, const std::vector<std::uint32_t>& stems, const DrapedLineSet& whole) {
        const std::vector<std::size_t>& todo = w.todo;
        w.written.assign(todo.size(), 0), w.needed.resize(todo.size());
        w.needed_ids.assign(todo.size(), {}), w.dropped.assign(todo.size(), {});
        parallel_chunks(todo.size(), 1, [&](std::size_t j0, std::size_t j1) {
            for (std::size_t j = j0; j < j1; ++j) {
                const std::size_t k = todo[j];
                const std::vector<std::uint32_t>& ids = file_ids(k);
                const std::unique_ptr<DrapedLineSet> level = lines_of(ids, stems, whole);
                std::vector<StemBound> bounds(ids.size());  // their lines' (crease_line_bound)
                for (std::size_t i = 0; i < ids.size(); ++i)
                    bounds[i] = crease_line_bound(*level, i, file_bound(k, i), parts_.lo, parts_.hi);
                const TileRest& rest = cut_some[k] ? cut_some[k]->rest : TileRest{};
                w.written[j] = write_line_tile(tile_path(cut_tile[k], cut_level[k]), tile_key(cut_tile[k], cut_level[k]),
                                               crease_lattice(g_), *level, ids, bounds, rest);
                if (!w.written[j]) {
                    w.needed_ids[j] = ids_of(k), w.needed[j] = lines_of(w.needed_ids[j], stems, whole);
                    continue;
                }
                // the stems needed whose line's bound passes, as a later query reading the file keeps
                for (std::size_t i = 0, n = 0; i < ids.size(); ++i) {
                    const std::uint32_t s = ids[i];
                    while (n < cuts[k + 1] - cuts[k] && missing[cuts[k] + n] < s) ++n;
                    if (n == cuts[k + 1] - cuts[k] || missing[cuts[k] + n] != s) continue;
                    (bound_passes(bounds[i]) ? w.needed_ids[j] : w.dropped[j]).push_back(s);
                }
                const int d = cut_d[k];
                if (d == 0) {
                    w.needed[j] = lines_of(w.needed_ids[j], stems, whole);
                    continue;
                }
                // thinned now, not once the query's stems are all built (a whole view of a large
                // DEM would hold every stem it needs at full detail first), and so its copy at the
                // query's detail, where one is kept
                const DrapedLineSet thin = thinned_lines(*level, detail_spacing(d));
                if (d >= crease_copy_detail &&
                    write_line_tile(tile_path(cut_tile[k], cut_level[k], d), tile_key(cut_tile[k], cut_level[k], d),
                                    crease_lattice(g_), thin, ids, bounds, rest))
                    w.written[j] = 2;
                w.needed[j] = lines_of(w.needed_ids[j], ids, thin);
            }
        });
    };
    const auto keep_written = [&](TileWrites& w) {
        for (std::size_t j = 0; j < w.todo.size(); ++j) {
            ++tiles_built_;
            if (w.written[j]) tiles_written_ += w.written[j];
            else writable_ = false;  // the tiles from now on built as needed, in memory only
            const std::size_t k = w.todo[j];
            dropped.insert(dropped.end(), w.dropped[j].begin(), w.dropped[j].end());
            keep(w.needed_ids[j], std::move(w.needed[j]), w.written[j] != 0, w.written[j] ? cut_d[k] : 0);
        }
        tile_built();
    };
    struct Writing {
        TileWrites w;
        std::vector<std::uint32_t> stems;
        DrapedLineSet whole;
    };
    std::unique_ptr<Writing> writing;  // the tile whose files are being written
    std::future<void> written;         // (declared last: waited for before what it reads goes)
    const auto finish_writing = [&] {
        if (!writing) return;
        written.get();
        keep_written(writing->w);
        writing.reset();
    };
    // with a store, each tile's build (every stem of its levels needed) runs beside the next
    // one's, which starts before this one's is waited for: what one runs on one core (its
    // trunks' climb, its copies, the joins) overlaps the other's, and the builds and the writes
    // keep both cores busy
    std::vector<std::size_t> group{0};  // cuts [group[j], group[j + 1]): the j-th tile's with cuts
    for (std::size_t k = 1; k <= cut_tile.size(); ++k)
        if (k == cut_tile.size() || cut_tile[k] != cut_tile[k - 1]) group.push_back(k);
    std::vector<std::uint8_t> was_read(cut_tile.size());
    for (std::size_t k = 0; k < cut_tile.size(); ++k) was_read[k] = read[k] != nullptr;
    const auto planned = [&](std::size_t j) {  // the cuts of group j not read, and their units' stems
        auto b = std::make_unique<Writing>();
        for (std::size_t k = group[j]; k < group[j + 1]; ++k)
            if (!was_read[k]) b->w.todo.push_back(k), b->stems = merged(std::move(b->stems), file_ids(k));
        return b;
    };
    std::vector<std::unique_ptr<Writing>> builds(group.size() - 1);  // the groups' builds started
    std::vector<std::future<void>> building(builds.size());  // (declared last: waited for before the builds go)
    std::size_t launched = 0;  // the groups before this one have been looked at for a build
    const auto launch = [&](std::size_t until) {  // the builds of groups up to `until` (exclusive) started
        for (; launched < std::min(until, builds.size()); ++launched) {
            std::unique_ptr<Writing> b = planned(launched);
            if (b->w.todo.empty()) continue;
            builds[launched] = std::move(b);
            building[launched] = std::async(std::launch::async, [this, w = builds[launched].get()] {
                w->whole = crease_part(g_, dir_, net_, *surface_, parts_, w->stems);
            });
        }
    };
    for (std::size_t j = 0; j + 1 < group.size(); ++j) {
        const std::size_t k0 = group[j], k1 = group[j + 1];
        for (std::size_t k = k0; k < k1; ++k)
            if (read[k]) keep(read_ids[k], std::move(read[k]), true, cut_d[k]);
        std::vector<std::size_t> todo;  // cuts of this tile still missing
        for (std::size_t k = k0; k < k1; ++k)
            if (!was_read[k]) todo.push_back(k);
        if (todo.empty()) continue;
        if (!loaded_ && parts_.sources.empty()) parts_.sources = reader_.sources();  // what crease_part reads
        if (!store_.folder.empty() && writable_) {
            surface();      // made here, before a build reads it on a thread
            launch(j + 2);  // this tile's build and the next one's
            std::unique_ptr<Writing> next = std::move(builds[j]);
            if (next) building[j].get();
            if (!next || next->w.todo != todo) {  // (the cuts not read are the cuts missing: never)
                next = std::make_unique<Writing>();
                next->w.todo = std::move(todo);
                for (std::size_t k : next->w.todo) next->stems = merged(std::move(next->stems), file_ids(k));
                next->whole = crease_part(g_, dir_, net_, surface(), parts_, next->stems);
            }
            check_part(next->whole.lines.size(), next->stems.size());
            finish_writing();
            if (writable_) {
                writing = std::move(next);
                written = std::async(std::launch::async, [&write_tile, w = writing.get()] { write_tile(w->w, w->stems, w->whole); });
                continue;
            }
            // a file before could not be written: this tile's stems kept whole, in memory
            const std::vector<std::uint32_t> need = missing_in(next->w.todo);
            keep(need, lines_of(need, next->stems, next->whole));
            tile_built();
            continue;
        }
        const std::vector<std::uint32_t> need = missing_in(todo);
        if (j < launched && builds[j] && builds[j]->w.todo == todo) {  // built ahead before a file could not be written
            building[j].get();
            const std::unique_ptr<Writing> b = std::move(builds[j]);
            keep(need, lines_of(need, b->stems, b->whole));
        } else {
            keep(need, std::make_unique<DrapedLineSet>(crease_part(g_, dir_, net_, surface(), parts_, need)));
        }
        tile_built();
    }
    finish_writing();
    tiles_written_ += copies;
    std::sort(dropped.begin(), dropped.end());
    std::vector<Pick> picks;
    picks.reserve(wanted.size());
    std::vector<std::size_t> thin;  // picks of lines at detail 0 wanted coarser (built here, kept)
    std::vector<int> pick_d;        // each pick's detail
    for (const Wanted& w : wanted) {
        const std::uint32_t* i = kept_.find(w.stem);
        const std::uint32_t* q = i ? nullptr : query_.find(w.stem);
        if (!i && !q) {
            if (std::binary_search(dropped.begin(), dropped.end(), w.stem)) continue;
            throw Error("drainage", "", "crease tiles lost stem " + std::to_string(w.stem), ExitCode::internal);
        }
        const auto [set, line] = i ? at_[*i] : query_at_[*q];
        if (i) {  // kept in memory, whole: its line's bound tested as a file's would be
            if (!bound_passes(crease_line_bound(*sets_[set], line, w.bound, parts_.lo, parts_.hi))) continue;
        }
        if (set_detail_[set] != w.d) thin.push_back(picks.size());
        picks.push_back({w.stem, sets_[set], line}), pick_d.push_back(w.d);
    }
    for (int d = 1; d <= crease_detail_levels && !thin.empty(); ++d) {  // thinned as the copies are
        DrapedLineSet full;
        std::vector<std::size_t> at;
        for (const std::size_t p : thin)
            if (pick_d[p] == d) {
                const DrapedLine& l = picks[p].set->lines[picks[p].line];
                DrapedLine c = l;
                c.first = std::uint32_t(full.vertices.size());
                full.vertices.insert(full.vertices.end(), picks[p].set->vertices.begin() + l.first,
                                     picks[p].set->vertices.begin() + l.first + l.count);
                full.lines.push_back(c), at.push_back(p);
            }
        if (at.empty()) continue;
        const auto coarse = std::make_shared<const DrapedLineSet>(thinned_lines(full, detail_spacing(d)));
        for (std::size_t j = 0; j < at.size(); ++j) picks[at[j]].set = coarse, picks[at[j]].line = std::uint32_t(j);
    }
    // the sets in files forgotten (the picks hold them while the caller uses them), and the list
    // of sets compacted once most of it is forgotten ones (a flight's frames, one after another)
    for (const auto& [set, line] : query_at_) sets_[set].reset();
    query_ = U32Map(), query_at_.clear();
    if (std::size_t(std::count(sets_.begin(), sets_.end(), nullptr)) * 2 > sets_.size()) {
        std::vector<std::uint32_t> moved(sets_.size());
        std::size_t n = 0;
        for (std::size_t i = 0; i < sets_.size(); ++i)
            if (sets_[i]) moved[i] = std::uint32_t(n), sets_[n] = std::move(sets_[i]), set_detail_[n++] = set_detail_[i];
        sets_.resize(n), set_detail_.resize(n);
        for (auto& [set, line] : at_) set = moved[set];
    }
    return picks;
}

void CreaseTiles::line_refs_by_row(glm::vec2 lo, glm::vec2 hi, const LineTest& may_show, const LineDetail& detail,
                                   const std::function<void(LineRefs)>& f) {
    built_in_query_ = false, progress_shown_ = 0.0;
    const std::size_t rows = (tiles_.size() + tiles_across_ - 1) / tiles_across_;
    for (std::size_t row = 0; row < rows; ++row) {
        progress_from_ = double(row) / double(rows), progress_share_ = 1.0 / double(rows);
        f(refs_of(picks_for_box(lo, hi, may_show, detail, row)));
    }
    progress_from_ = 0.0, progress_share_ = 1.0;
    if (build_progress_ && progress_shown_ > 0.0 && progress_shown_ < 1.0) build_progress_(1.0);  // the rows after built none
    builds_ += built_in_query_;
}

CreaseTiles::LineRefs CreaseTiles::refs_of(const std::vector<Pick>& picks) {
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
                                         const LineTest& may_show, const LineDetail& detail) {
    built_in_query_ = false;
    const std::vector<Pick> picks = picks_for_box(lo, hi, may_show, detail);
    builds_ += built_in_query_;
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
