// The creases of a drainage database that stores what building them reads (DrainageDb::
// crease_source, crease_source.hpp) instead of the creases: the tile index (with each stem's
// bound) decoded on the first query, the grid and directions when a stem is first built here (the
// accumulation, orders and basins then made again from the directions), and the creases built
// stem by stem where a query's plan box and line test need them (crease_tiles.hpp: the whole
// build's lines bit for bit), each kept for the next query of this object (the frames of one
// process); nothing is written.
// Thread-safe: queries from several threads (frames prepared on threads) run one at a time (a
// build runs on all cores).
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/vec2.hpp>

#include "drainage/crease_tiles.hpp"
#include "drainage/line_set.hpp"

namespace penink {

class StoredCreases {
public:
    // `source`: DrainageDb::crease_source (not empty).
    explicit StoredCreases(std::vector<std::uint8_t> source);
    ~StoredCreases();

    // The creases meeting the closed plan box [lo, hi] and passing may_show (CreaseTiles::
    // LineTest: empty, all) and maybe more, in the stored order, indexed: lines_meeting_box on it
    // gives exactly the lines passing may_show that a database holding every crease gives for the
    // box. Throws penink::Error("drainage", "", ..., internal) when the source does not decode (it
    // was checked by the database's checksum: a builder's fault).
    DrapedLineSet lines_for_box(glm::vec2 lo, glm::vec2 hi, const CreaseTiles::LineTest& may_show = {});
    // The same lines as records and pointers to their vertices in the kept lines (valid while this
    // object lives): what a frame selects from without copying the vertices.
    CreaseTiles::LineRefs line_refs_for_box(glm::vec2 lo, glm::vec2 hi, const CreaseTiles::LineTest& may_show = {});

    // Stems in all, built so far and their vertices, queries that built stems (0 before the first
    // query).
    std::size_t stem_count() const;
    std::size_t stems_built() const;
    std::size_t vertices_built() const;
    std::size_t builds() const;

private:
    struct Decoded;
    mutable std::mutex mutex_;
    std::vector<std::uint8_t> source_;
    std::unique_ptr<Decoded> decoded_;
    CreaseTiles& tiles();  // decoded on first use; under mutex_
    std::size_t count(std::size_t (CreaseTiles::*of)() const) const;  // of the tiles, 0 before
};

}  // namespace penink
