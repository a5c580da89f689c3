// lines_in_box: the runs of each line's vertices inside the plan box [lo, hi] (edges included),
// each widened by the one vertex beyond the box at each cut; divide_polylines: each DvPolyline
// as the index list first .. first + count - 1. Vertices are hand-placed at whole metres, well
// clear of the box edges except where a test puts one exactly on an edge (compared exactly).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "drainage/stems.hpp"

using namespace penink;

namespace {

using Lines = std::vector<std::vector<std::uint32_t>>;

DvVertices vertices(const std::vector<glm::vec2>& xy) {
    DvVertices v;
    for (const glm::vec2& p : xy) v.push_back(DvVertex{p.x, p.y, 100.0f, 0.5f});
    return v;
}

const glm::vec2 lo{0, 0}, hi{10, 10};

// Two far-away vertices first, so a line's indices differ from its vertex positions in the list.
// Then a line (vertices 2-9) that enters the box, leaves it, comes back and leaves again:
//   2 (-5, 5) out, 3 (2, 5) in, 4 (8, 5) in, 5 (15, 5) out, 6 (20, 8) out,
//   7 (8, 8) in, 8 (-3, 8) out, 9 (-6, 9) out.
DvVertices twice_crossing() {
    return vertices({{500, 500}, {-500, 500}, {-5, 5}, {2, 5}, {8, 5}, {15, 5}, {20, 8}, {8, 8}, {-3, 8}, {-6, 9}});
}

}  // namespace

TEST(StemSelection, LineCrossingTheBoxTwiceGivesTwoPieces) {
    const DvVertices v = twice_crossing();
    const Lines out = lines_in_box({{2, 3, 4, 5, 6, 7, 8, 9}}, v, lo, hi);
    // Piece 1: inside 3, 4 with 2 before and 5 after; piece 2: inside 7 with 6 and 8 around it.
    // 9 (beyond 8) and the second outside vertex 6 -> 5 are not repeated.
    EXPECT_EQ(out, (Lines{{2, 3, 4, 5}, {6, 7, 8}}));
    for (const auto& piece : out) {  // exactly one vertex beyond the box at each end
        const auto in = [&](std::uint32_t i) { return v[i].x >= 0 && v[i].x <= 10 && v[i].y >= 0 && v[i].y <= 10; };
        EXPECT_FALSE(in(piece.front()));
        EXPECT_FALSE(in(piece.back()));
        for (std::size_t k = 1; k + 1 < piece.size(); ++k) EXPECT_TRUE(in(piece[k]));
    }
}

TEST(StemSelection, IndicesAreThoseOfTheLineNotPositions) {
    // The same vertices walked backwards: pieces come out in the line's own order.
    const DvVertices v = twice_crossing();
    const Lines out = lines_in_box({{9, 8, 7, 6, 5, 4, 3, 2}}, v, lo, hi);
    EXPECT_EQ(out, (Lines{{8, 7, 6}, {5, 4, 3, 2}}));
}

TEST(StemSelection, WhollyInsideIsWholeWhollyOutsideIsNothing) {
    const DvVertices v = vertices({{1, 1}, {5, 2}, {9, 9}, {20, 1}, {25, 5}, {-4, -4}});
    EXPECT_EQ(lines_in_box({{0, 1, 2}}, v, lo, hi), (Lines{{0, 1, 2}}));
    EXPECT_TRUE(lines_in_box({{3, 4, 5}}, v, lo, hi).empty());
    EXPECT_TRUE(lines_in_box({}, v, lo, hi).empty());
    EXPECT_TRUE(lines_in_box({{}}, v, lo, hi).empty());
    // Several lines: each gives its own pieces, in line order.
    EXPECT_EQ(lines_in_box({{3, 4, 5}, {0, 1, 2}, {2, 1}}, v, lo, hi), (Lines{{0, 1, 2}, {2, 1}}));
}

TEST(StemSelection, CutAtOnlyOneEndAndEdgesCountAsInside) {
    // Starts inside, leaves: no vertex before; enters and ends inside: no vertex after.
    // Vertex 2 lies exactly on x = hi.x and 5 exactly on the corner lo: both inside.
    const DvVertices v = vertices({{1, 1}, {5, 5}, {10, 5}, {12, 5}, {-2, 0}, {0, 0}, {3, 3}});
    EXPECT_EQ(lines_in_box({{0, 1, 2, 3}}, v, lo, hi), (Lines{{0, 1, 2, 3}}));
    EXPECT_EQ(lines_in_box({{0, 1, 3, 4}}, v, lo, hi), (Lines{{0, 1, 3}}));
    EXPECT_EQ(lines_in_box({{4, 5, 6}}, v, lo, hi), (Lines{{4, 5, 6}}));
    EXPECT_EQ(lines_in_box({{3, 4, 6}}, v, lo, hi), (Lines{{4, 6}}));
    // A single inside vertex between two outside ones.
    EXPECT_EQ(lines_in_box({{3, 1, 4}}, v, lo, hi), (Lines{{3, 1, 4}}));
}

TEST(StemSelection, DividePolylinesAreConsecutiveIndexRanges) {
    DrainageDb db;
    db.divide_vertices = vertices({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}, {6, 0}});
    db.divides = {DvPolyline{0, 3}, DvPolyline{3, 2}, DvPolyline{5, 0}, DvPolyline{5, 2}};
    EXPECT_EQ(divide_polylines(db), (Lines{{0, 1, 2}, {3, 4}, {}, {5, 6}}));
    db.divides.clear();
    EXPECT_TRUE(divide_polylines(db).empty());
}
