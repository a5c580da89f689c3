// The creases of a drainage database that stores what building them reads (DrainageDb::
// crease_source, crease_source.hpp) instead of the creases: the tile index (with each stem's
// bound) decoded on the first query, the grid and directions when a stem is first built here (the
// network's orders and flows then decoded by blocks where the stems' walks reach, from the
// network the source stores: cell_blocks.hpp), and the creases built
// stem by stem where a query's plan box and line test need them (crease_tiles.hpp: the whole
// build's lines bit for bit), each kept for the next query of this object (the frames of one
// process). Given a folder, every tile whose stems a query needs is kept there whole, in a file of
// its own (crease_tiles.hpp TileStore, line_tile_files.hpp), so the next process reads it instead
// of building it; a folder that cannot be written keeps only the stems built in memory. Tile files
// are keyed by the database's version and a hash of the stored source bytes: a file of another
// network or builder is built again and rewritten.
// Thread-safe: queries from several threads (frames prepared on threads) run one at a time (a
// build runs on all cores).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/crease_source.hpp"
#include "drainage/crease_tiles.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/line_set.hpp"

namespace penink {

// The folder beside a drainage database file that keeps its crease tiles: `<dv_path>.tiles`.
std::string crease_tile_folder(const std::string& dv_path);
// Removes that folder's tile files and the folder (when empty then): called when a database file is
// written anew, whose tiles are all of another key. Errors are ignored (files left are rebuilt
// when read: their key differs).
void remove_crease_tiles(const std::string& dv_path);

class StoredCreases {
public:
    // `source`: DrainageDb::crease_source (not empty); `folder`: where tile files are kept (none:
    // empty, nothing written).
    explicit StoredCreases(std::vector<std::uint8_t> source, std::string folder = {});
    // A source left in the database file (DrainageDb::crease_source_pages, _size and _sums): only
    // the pages a query needs are read.
    StoredCreases(std::shared_ptr<const CheckedBlocks> pages, std::uint64_t size, std::vector<std::uint64_t> sums,
                  std::string folder = {});
    // The database's source either way (has_crease_source): its bytes copied, or its pages shared;
    // take: moved out of db (which is left without one), with the grid, directions and network
    // of a build in this process (DrainageDb::built_network): the first stems built from them.
    static std::shared_ptr<StoredCreases> of(const DrainageDb& db, std::string folder = {});
    static std::shared_ptr<StoredCreases> take(DrainageDb& db, std::string folder = {});
    ~StoredCreases();

    // The creases meeting the closed plan box [lo, hi] and passing may_show (CreaseTiles::
    // LineTest: empty, all) and maybe more, in the stored order, indexed: lines_meeting_box on it
    // gives exactly the lines passing may_show that a database holding every crease gives for the
    // box. Throws penink::Error("drainage", "", ..., internal) when the source does not decode (it
    // was checked by the database's checksum: a builder's fault).
    DrapedLineSet lines_for_box(glm::vec2 lo, glm::vec2 hi, const CreaseTiles::LineTest& may_show = {},
                                const CreaseTiles::LineDetail& detail = {});
    // The same lines as records and pointers to their vertices in the kept lines, a row of tiles at
    // a time (CreaseTiles::line_refs_by_row): what a frame selects from without copying the vertices.
    void line_refs_by_row(glm::vec2 lo, glm::vec2 hi, const CreaseTiles::LineTest& may_show,
                          const CreaseTiles::LineDetail& detail, const std::function<void(CreaseTiles::LineRefs)>& f);

    // Stems in all, built so far and their vertices, queries that built stems (0 before the first
    // query).
    std::size_t stem_count() const;
    std::size_t stems_built() const;
    std::size_t vertices_built() const;
    std::size_t builds() const;
    // Called while a query builds tiles (CreaseTiles::on_build_progress); set before the first
    // query.
    void on_build_progress(std::function<void(double)> f) { build_progress_ = std::move(f); }
    // Where the first build reads the DEM's heights from by blocks when the source refers to its
    // DEM (decode_crease_source's `heights`: a render's terrain cache) instead of reading the DEM
    // whole; set before the first query.
    void use_node_heights(NodeHeights h) { heights_ = std::move(h); }
    // The grid, directions and network of the build in this process that wrote the database read
    // (as take() hands on DrainageDb::built_network): the first stems built from them. Before the
    // first query.
    void use_built_network(BuiltNetworkHandle built) { built_ = std::move(built.arrays); }
    // Called once with the drainage grid's size (its points: cols x rows), before the first query
    // that builds stems decodes the grid, directions and network (not where they are a build's of
    // this process, nor for queries whose tiles are all in files): a render checks there that the
    // build fits its memory (it may throw, and the query throws that). Set before the first query.
    void before_first_decode(std::function<void(int cols, int rows)> f) { before_decode_ = std::move(f); }
    std::size_t tiles_read() const;     // tile files read
    std::size_t tiles_written() const;  // tile files written

private:
    struct Decoded;
    mutable std::mutex mutex_;
    std::vector<std::uint8_t> source_;
    std::shared_ptr<const CheckedBlocks> pages_;  // or the source's pages in its file
    std::string dem_;                             // DrainageDb::crease_source_dem
    std::uint64_t size_ = 0;
    std::vector<std::uint64_t> sums_;  // its pages' checksums (made from source_ where not given)
    std::string folder_;
    std::shared_ptr<BuiltNetwork> built_;  // the build's arrays, where this process built them (take)
    CreaseSourceBytes bytes() const;
    std::function<void(double)> build_progress_;
    NodeHeights heights_;
    std::function<void(int, int)> before_decode_;
    std::unique_ptr<Decoded> decoded_;
    CreaseTiles& tiles();  // decoded on first use; under mutex_
    std::size_t count(std::size_t (CreaseTiles::*which)() const) const;  // of the tiles, 0 before
};

}  // namespace penink
