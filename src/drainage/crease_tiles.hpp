// The creases of a drainage network built where they are needed: the stems grouped in square
// tiles of the drainage grid by their source cell, each stem built (crease_part, draped_lines.hpp:
// the whole build's line bit for bit) the first time a query needs it, and kept. A query for a
// plan box needs every stem whose reach (stem_reach.hpp: where its crease can lie, from its cells)
// meets the box, found through the tiles' reach boxes, so the lines it returns include every line
// of the whole build meeting the box; given a test of a line's record (LineCulling's screen size:
// its box and 3-D length), only the stems whose bound (StemBound: their reach's box and a bound
// of their length) passes it are built and returned: a line whose bound fails fails too.
// The stems a query needs that are not built yet are built a tile's (256 x 256 cells) at a time,
// crease_part on all cores: one part of every stem costs more than the tiles one by one (on
// jacksboro refined to 0.6", 2015 x 1720 cells, all stems 3.1 s in one part, 1.8 s in 56 tiles:
// bench/line_parts_bench.cpp, a loaded machine), a tile's alone about 0.03 s. With a store, a
// tile's build runs beside the next tile's (what one runs on one core overlaps the other's).
// With a tile store (a folder and a key), a tile's stems are kept on disk by length: each level
// (crease_tile_level: the stems' plan bound under 4, 8, ..., 256 cells, or longer) of each tile in a
// file of its own (line_tile_files.hpp). A level of a tile with stems a query needs that are not
// kept is first looked for in its file (read when its key, sizes and checksum hold, and it holds
// every stem of the level the query needs), else all its stems are built (or only those the query
// needs, when they are few: crease_partial_share) and its file written, so the next process reads
// what this one built; either
// way only the stems the query needs are kept in memory (a later query needing others reads the
// file again). A view of a whole large DEM, which can show only long stems, so reads and builds
// only the levels of long ones. Without a store, or once a file cannot be written, only the stems
// needed are built and nothing is written.
// A query visits only the levels of the tiles meeting its box whose summary (the box of their
// stems' bounds and the largest length bound) passes its test; a whole view of a large DEM so
// visits the stems of the long levels alone.
// Made once (the constructor): the stems' sources and box (stem_parts), each stem's bound and
// each tile's reach, from one walk of every stem (its cells, 4 B a vertex while it runs).
// Not thread-safe: one query at a time.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/dem_surface.hpp"
#include "drainage/draped_lines.hpp"
#include "core/u32_map.hpp"
#include "drainage/line_tile_files.hpp"
#include "drainage/stem_reach.hpp"

namespace penink {

// What a CreaseTiles is made from besides the network: the tile side (cells), the stems' sources
// and box (stem_parts), each stem's bound (stem_bound of its reach's plan box and
// stem_cell_travel, across parts' box; in parts.sources' order) and each tile's plan box of its
// stems' reaches (row-major tiles; empty, hi < lo, for a tile without stems). Made by one walk of
// every stem (crease_tile_index); a database stores it (crease_source.hpp) so that a render makes
// its tiles without that walk.
// z_top: drape_height_top of the grid, above every crease vertex.
// units: crease_units of the above (what a query tests before it needs any stem). An index of
// units alone (parts.sources and stems empty; parts' box, lo, hi, z_top and units given) is what a
// frame whose stems are all in tile files needs (decode_crease_source's SourcePart::units).
// A tile's stems of one level (crease_tile_level): how many, and what bounds every one of them:
// the box of their bounds' boxes (stem_bound_box) and their largest plan and rise bounds (a test
// of a bound grows with its box and its length, so a unit whose summary fails has no stem that
// passes).
struct CreaseUnit {
    std::uint32_t tile = 0, level = 0, count = 0;
    glm::vec2 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
    StemBound most;  // plan and rise: the largest (bfloat16 bits order as their values)
    bool operator==(const CreaseUnit&) const = default;
};
struct CreaseTileIndex {
    int side = 256;
    StemParts parts;
    std::vector<StemBound> stems;
    std::vector<glm::vec2> lo, hi;
    float z_top = -std::numeric_limits<float>::infinity();
    std::vector<CreaseUnit> units;
};
// z_top: drape_height_top(g) when found before (NaN: found here).
CreaseTileIndex crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                                  int tile = 256, float z_top = std::numeric_limits<float>::quiet_NaN());

// A crease tile index as a crease source stores it (crease_source.hpp): `index` without its stems'
// bounds (index.stems empty; its parts, tile boxes, z_top and units), and each unit's stems coded on
// their own, in index.units' order: ids[u] (stem_reach.hpp encode_stem_ids of the unit's stems,
// ascending) and bounds[u] (encode_stem_bounds of theirs).
struct CodedCreaseIndex {
    CreaseTileIndex index;
    std::vector<std::vector<std::uint8_t>> ids, bounds;
};
// `index` (its stems' bounds given) so coded, on a grid of cols x rows cells `cell` metres wide;
// the units' stems coded on all cores.
CodedCreaseIndex code_crease_index(CreaseTileIndex index, int cols, int rows, double cell);
// code_crease_index(crease_tile_index(g, dir, net, tile, z_top), g.cols, g.rows, g.dx) byte for
// byte, made a row of tiles at a time: the stems are in the order of their source cells, so a
// row's are consecutive; each row's are walked (for_each_stem_cells, on all cores), bounded, put
// in their units and coded before the next row's, so only one row's bounds and members are held
// (12 B and 4 B a stem: on jacksboro refined 29 times, 36.5 M stems, 0.58 GB for the whole index
// and its members at once).
CodedCreaseIndex coded_crease_tile_index(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                         const FlowNetwork& net, int tile = 256,
                                         float z_top = std::numeric_limits<float>::quiet_NaN());

// The bound of line i of `lines` (a stem's crease, built whole: detail 0) kept in its tile's
// files and tested by a query before it gives the line (stem_line_bound of its vertices' box,
// plan length and rise, no looser than `reach`, its stem's bound in the index, on the stems' box
// [lo, hi]): the index's bound is what a query tests before a line is read or built, this one
// what it tests before the line is given, however it was found (read, built, or kept from a
// query before), so the lines given are the same either way. On a whole view of jacksboro refined
// 29 times it passes 8.8 M of the 14.6 M vertices whose stems' index bounds pass.
StemBound crease_line_bound(const DrapedLineSet& lines, std::size_t i, const StemBound& reach, glm::vec2 lo, glm::vec2 hi);

// The level of a stem whose bound is b on a grid of cells `cell` metres wide (DrainageGrid::dx):
// 0 to 7 as stem_bound_plan(b) is under 4, 8, 16, ..., 256 cells, or longer.
inline constexpr int crease_tile_levels = 8;
int crease_tile_level(const StemBound& b, double cell);

// The units of the stems of `index` (its parts and stems) on a grid of cols x rows cells `cell`
// metres wide, in tile then level order, those with stems alone; on all cores.
std::vector<CreaseUnit> crease_units(const CreaseTileIndex& index, int cols, int rows, double cell);
// The stems of each unit of `index` (index.units' order; ids ascending), from its parts and stems;
// throws penink::Error(internal) when they do not fit the units (a stem of a tile and level
// without a unit, a count that differs).
std::vector<std::vector<std::uint32_t>> crease_unit_stems(const CreaseTileIndex& index, int cols, int rows, double cell);

// Where a CreaseTiles made from an index of units alone finds the rest: one unit's stems (`unit`:
// its place in CreaseTileIndex::units; ids ascending and their bounds; called from several threads
// at once), the whole index, and the stems' sources alone (`sources`: StemParts::sources, what
// building stems needs besides their units; without it a build loads the whole index). Each
// throws penink::Error on bytes that do not decode.
struct CreaseIndexReader {
    std::function<void(std::size_t unit, std::vector<std::uint32_t>& ids, std::vector<StemBound>& bounds)> unit;
    std::function<CreaseTileIndex()> whole;
    std::function<std::vector<std::uint32_t>()> sources;
};

// A unit a query needs stems of but whose file it cannot read is built and written whole, unless
// the stems the query needs (their index bounds pass) weigh crease_partial_share of its stems'
// plan bounds (what their build costs) or less: then those alone are built and written, a file of
// some of the unit's stems. A query reads such a file when it holds every stem of the unit that
// the query needs, else builds the unit whole and writes its file over it. The index bounds are
// loose (on a whole view of jacksboro refined 29 times a line's length bound is 0.55 to 0.7 of its
// stem's), so the whole view's units of stems shorter than those it draws are mostly stems it does
// not need: there, 232 k of the 335 k stems of the level of stems 128 to 256 cells long.
inline constexpr double crease_partial_share = 0.5;

// Copies of a unit's lines with fewer vertices, for frames that cannot tell them from the lines:
// detail d (1 to crease_detail_levels) keeps vertices about 2^d cells apart (thinned_lines with a
// spacing of 2^d DrainageGrid::dx). A query asks for the coarsest detail whose spacing its
// LineDetail allows in each unit's box; a copy of detail crease_copy_detail or more is kept in a
// file of its own beside the unit's, thinned from it when first asked for (half its vertices or
// fewer). On a warm whole view of jacksboro refined 29 times (117 M cells) 3197 units are read at
// detail 1 and 2098 at detail 2: their copies at detail 1 take the folder from 219 to 294 MB and
// halve the vertices decoded, 32.4 M to 18.7 M (user CPU 6.0-6.2 s to 5.2 s, the SVG the same).
inline constexpr int crease_detail_levels = 6, crease_copy_detail = 1;
// The lines of `from` with their vertices thinned: a line's first vertex, then each vertex whose
// 3-D distance (unexaggerated) from the last one kept is `spacing` metres or more, and its last
// vertex; records and index made again (index_lines). Every line keeps at least one vertex (two
// where it had two); thinning the result again with the same spacing gives it unchanged.
DrapedLineSet thinned_lines(const DrapedLineSet& from, double spacing);

// Where built tiles are kept between processes: one file a tile in `folder` (none: empty), each
// keyed by hash64 of `key` (the caller's: what the network was built from), the tile size, the
// tile's index and the level.
struct TileStore {
    std::string folder;
    std::uint64_t key = 0;
};

class CreaseTiles {
public:
    // g, dir and net must outlive this (g.z: the original elevations, as build_draped_lines reads);
    // with before_first_build, only g's cols and rows are read before the first build.
    // On a DEM without relief (has_relief) the whole build keeps no creases: make none there.
    CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net, int tile = 256,
                TileStore store = {});
    // The same from a stored index (crease_tile_index of this network; index.side is the tile size).
    // An index of units alone (CreaseTileIndex::units, no stems) with a reader of the rest: a
    // query reads the tile files of the units whose summary passes (they carry their stems' ids
    // and bounds), tests the stems of a unit without a sound file by reader.unit, and asks for the
    // stems' sources (reader.sources, once; without it the whole index) only to build stems, whose
    // units' ids and bounds reader.unit gave. Throws penink::Error(internal) on an index that does
    // not fit the grid.
    CreaseTiles(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                CreaseTileIndex index, TileStore store = {}, CreaseIndexReader reader = {});

    // Whether a stem's crease may be drawn, from its bound alone (its box lo, hi as stem_bound_box
    // gives it; its length at exaggeration e: stem_bound_length; z_top: a height no crease vertex
    // exceeds, CreaseTileIndex::z_top): it must pass a stem whenever it passes the stem's line (a
    // test growing with the length and the box, as LineCulling's screen size does). Empty: every
    // stem.
    using LineTest = std::function<bool(const StemBound& bound, glm::vec2 lo, glm::vec2 hi, float z_top)>;
    // The largest spacing (metres, unexaggerated 3-D) of a line's vertices that a frame cannot tell
    // from the line anywhere in the plan box [lo, hi] below z_top (0: every vertex); a unit's lines
    // are given at the coarsest detail (crease_detail_levels) whose spacing is at most that in its
    // summary's box. Empty: every vertex everywhere.
    using LineDetail = std::function<double(glm::vec2 lo, glm::vec2 hi, float z_top)>;

    // The stems whose bound's box meets the closed plan box [lo, hi] and passes `may_show`, built
    // where not yet, in stem order (network_stems' ids in `ids`), indexed: lines_meeting_box on
    // it gives the whole build's lines meeting the box (those passing may_show, which the others
    // fail), in the same order, equal bit for bit.
    // With `detail`, each line as thinned_lines gives it at its unit's detail.
    DrapedLineSet lines_for_box(glm::vec2 lo, glm::vec2 hi, std::vector<std::uint32_t>* ids = nullptr,
                                const LineTest& may_show = {}, const LineDetail& detail = {});
    // The same lines without copying their vertices: each line's record (box, length, count,
    // order; `first` meaningless) and a pointer to its vertices where it was built or read, which
    // stays valid and unchanged as long as this LineRefs lives (it holds the sets pointed into).
    struct LineRefs {
        std::vector<DrapedLine> lines;
        std::vector<const DrapedVertex*> vertices;
        std::vector<std::shared_ptr<const DrapedLineSet>> hold;
    };
    // They come a row of tiles at a time, north to south: f(refs) with the lines of the stems
    // whose source lies in that row (stems are numbered by source cell, row-major, so the rows'
    // lines one after another are lines_for_box's, in its order), each row's sets let go once
    // f returns: the lines held follow one row of the DEM, not the whole frame. One query for
    // builds().
    void line_refs_by_row(glm::vec2 lo, glm::vec2 hi, const LineTest& may_show, const LineDetail& detail,
                          const std::function<void(LineRefs)>& f);

    // Called once, before the first stem is built: a caller that made g, dir and net with their
    // sizes only fills them there.
    void before_first_build(std::function<void()> f) { before_build_ = std::move(f); }
    // Called while a query builds tiles: the fraction of the tiles it builds done so far (after
    // each tile, 1 after the last; not called for a query that builds none; a query by rows: each
    // row's tiles within its share of the rows, rising from 0 to 1 over the whole query).
    void on_build_progress(std::function<void(double)> f) { build_progress_ = std::move(f); }

    std::size_t tile_count() const { return tiles_.size(); }
    std::size_t stem_count() const { return stem_count_; }
    // The index the tiles were made from (crease_tile_index's, or the one given; the whole one).
    CreaseTileIndex index();
    // Whether the whole index is in memory (made, given, or loaded by a query).
    bool index_loaded() const { return loaded_; }
    // Stems a query read from a tile file or built for one are not kept after it (the next query
    // needing them reads the file again: memory follows the frame); those built without a file
    // are kept for the next query.
    std::size_t stems_built() const { return stems_built_; }        // built or read by the queries so far
    std::size_t vertices_built() const { return vertices_built_; }  // their lines' vertices
    std::size_t builds() const { return builds_; }                  // queries that built or read stems
    std::size_t tiles_read() const { return tiles_read_; }          // tile files read (each time)
    std::size_t tiles_built() const { return tiles_built_; }        // tiles built whole for their files
    std::size_t tiles_written() const { return tiles_written_; }    // tile files written
    std::size_t sets_held() const { return sets_.size(); }          // line sets listed (kept ones, forgotten ones)

private:
    struct Pick {
        std::uint32_t stem;
        std::shared_ptr<const DrapedLineSet> set;
        std::uint32_t line;
    };
    // built where needed, in stem order, each at its unit's detail; those of row `row` of tiles
    // alone unless all_rows (built_in_query_ set when it read or built stems)
    static constexpr std::size_t all_rows = std::size_t(-1);
    std::vector<Pick> picks_for_box(glm::vec2 lo, glm::vec2 hi, const LineTest& may_show, const LineDetail& detail,
                                    std::size_t row = all_rows);
    static LineRefs refs_of(const std::vector<Pick>& picks);
    // The detail a query gives unit u's lines, and the file of unit (k, l) at detail d read into
    // `out` (d > 0: its copy, else its lines read at detail 0, thinned, and the copy written)
    // (0: no file read; 1: read; 2: read, and the copy written)
    int unit_detail(const CreaseUnit& u, const LineDetail& detail) const;
    // (need: line_tile_files.hpp's; none decoded where it says none is needed. enough: whether a
    // copy of some of the unit's stems, read first, holds what the query needs; else the file at
    // detail 0 is read too)
    int read_unit(std::size_t k, int l, int d, TileLines& out, const TileNeed& need = {}, const TileNeed& enough = {}) const;
    double detail_spacing(int d) const;  // metres between a copy's vertices at detail d
    struct Tile {
        std::array<std::vector<std::uint32_t>, crease_tile_levels> stems;  // ids by level, ascending (loaded_)
        std::array<CreaseUnit, crease_tile_levels> unit;                   // count 0: no stem of that level
        std::array<std::uint32_t, crease_tile_levels> at{};                // its place in the index's units
        glm::vec2 lo{0.0f}, hi{-1.0f};     // plan box of its stems' reaches
    };
    const DrainageGrid& g_;
    const std::vector<std::uint8_t>& dir_;
    const FlowNetwork& net_;
    int side_ = 256;
    StemParts parts_;  // its box always, its sources once loaded_ or a query built stems
    std::vector<StemBound> bounds_;  // once loaded_
    float z_top_;
    std::vector<Tile> tiles_;
    std::size_t stem_count_ = 0;
    bool loaded_ = false;
    std::size_t tiles_across_ = 1;   // tiles in a row
    bool built_in_query_ = false;
    double progress_from_ = 0.0, progress_share_ = 1.0, progress_shown_ = 0.0;  // build_progress_'s span
    CreaseIndexReader reader_;
    void take_index(CreaseTileIndex index);  // the whole index's stems into tiles_ (checked against the units)
    void load_index();                       // reader_.whole's, once
    // the lines built so far, one set a crease_part; stem s's is line at_[i].second of
    // sets_[at_[i].first], i = its entry in kept_ (the stems kept for later queries: built without
    // a file) or in this query's query_ (those read from or written to a file this query)
    std::vector<std::shared_ptr<const DrapedLineSet>> sets_;
    std::vector<std::uint8_t> set_detail_;  // each set's detail
    std::vector<std::pair<std::uint32_t, std::uint32_t>> at_, query_at_;
    U32Map kept_, query_;
    std::size_t stems_built_ = 0, vertices_built_ = 0, builds_ = 0;
    TileStore store_;
    bool writable_ = true;  // false once a tile file could not be written
    std::size_t tiles_read_ = 0, tiles_built_ = 0, tiles_written_ = 0;
    DemSurface& surface();  // made with the first build (after before_first_build)
    // keeps `lines` (line i: stem ids[i]) as a new set; for this query alone when on_disk
    void keep(const std::vector<std::uint32_t>& ids, std::unique_ptr<DrapedLineSet> lines, bool on_disk = false,
              int detail = 0);
    // of the file of level l of tile k at detail d, and its path
    std::uint64_t tile_key(std::size_t k, int l, int d = 0) const;
    std::string tile_path(std::size_t k, int l, int d = 0) const;
    std::unique_ptr<DemSurface> surface_;  // made with the first build
    std::function<void()> before_build_;
    std::function<void(double)> build_progress_;
};

}  // namespace penink
