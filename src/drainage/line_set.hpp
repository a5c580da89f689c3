// Creases (drainage stems) and ridges (basin divides) as the drainage database stores them for
// drawing (Mower, "Concurrent Drainage Network Rendering": the drainage vertices draped on the PN
// surface): smoothed and draped once when the database is built (draped_lines.hpp), each vertex
// with its unexaggerated z and the unit PN normal there, each line with its plan bounding box,
// 3-D length and Strahler order, and a spatial index so that a frame picks the lines meeting its
// modelled box without a pass over every vertex.
// Frame: the Terrain's local metres (x east, y north, z elevation, unexaggerated). Exaggerating
// by e: z' = e z, normal' = normalize(e nx, e ny, nz) (exact for a height field's normal).
// Index: loose grid levels. Level k has square cells of side cell * 2^k from `origin`; a line
// goes to the smallest level whose side is at least its box's larger side, in the cell holding
// its box's centre, so its box lies within that cell grown by half a side all round; levels are
// added until one cell covers every line. A query visits, on each level, the cells whose grown
// square meets the box, and tests the boxes of their lines.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "core/big_allocator.hpp"

namespace penink {

// 28 bytes, no padding (the DV file stores the array as it is).
struct DrapedVertex {
    float x, y, z;     // local metres; z on the PN surface (off it: the drainage vertex's own z)
    float nx, ny, nz;  // unit PN normal; zero off the surface (nodata): never drawn
    float flow;        // normalised flow (stems; see DvVertex), 0 on divides
    bool operator==(const DrapedVertex&) const = default;
};
static_assert(sizeof(DrapedVertex) == 28);

using DrapedVertices = std::vector<DrapedVertex, UninitAllocator<DrapedVertex>>;

struct DrapedLine {
    glm::vec2 lo{0.0f}, hi{0.0f};    // plan bounding box of its vertices, local metres
    float length = 0.0f;             // 3-D length, metres, unexaggerated (at e at most max(1, e) times this)
    std::uint32_t first = 0, count = 0;  // vertices [first, first + count)
    std::uint8_t order = 0;          // Strahler order of a stem (at its end); 0 for a divide
    bool operator==(const DrapedLine&) const = default;
};

struct LineIndex {
    glm::vec2 origin{0.0f};  // lower-left corner of every level's cell (0, 0)
    float cell = 1.0f;       // side of a level-0 cell, metres (> 0)
    std::vector<std::uint32_t> level_cols, level_rows;  // cells per level
    std::vector<std::uint32_t> start{0};  // CSR: the cells of level 0, 1, ... row-major (row 0 south), + 1
    std::vector<std::uint32_t> ids;    // line ids, ascending within a cell
    bool operator==(const LineIndex&) const = default;
};

struct DrapedLineSet {
    DrapedVertices vertices;
    std::vector<DrapedLine> lines;  // consecutive vertex ranges, in the order the builder makes them
    LineIndex index;
    bool operator==(const DrapedLineSet&) const = default;
};

// Fills set.lines[*].lo, hi, length from the vertices, then set.index.
void index_lines(DrapedLineSet& set);

// The ids of the lines whose bounding box meets the closed box [lo, hi], ascending.
std::vector<std::uint32_t> lines_meeting_box(const DrapedLineSet& set, glm::vec2 lo, glm::vec2 hi);

// What every reader relies on: lines' vertex ranges consecutive and covering the vertices, each
// with at least one vertex; the index's levels, offsets and ids in range, every line in it once.
bool line_set_ok(const DrapedLineSet& set);
// The same for a set whose `vertex_count` vertices are kept elsewhere (set.vertices unused).
bool line_set_ok(const DrapedLineSet& set, std::size_t vertex_count);

}  // namespace penink
