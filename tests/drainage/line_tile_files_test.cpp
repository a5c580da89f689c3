// Tile files of crease lines (src/drainage/line_tile_files.hpp): lines on the lattice, their
// stems' ids and bounds come back bit for bit, coded in a few bytes a vertex; lines off the lattice
// are not written; any damage, another key or a cut reads as absent.
#include "drainage/line_tile_files.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "support/temp_dir.hpp"

namespace penink {
namespace {

// Lines like draped creases, of cells 14.9 m wide: a walk of about a cell a step over a smooth
// surface, with its normals and a flow growing downstream; one line of a single vertex, signed
// zeros, a zero normal, a normal z an ulp off its x and y's, and a NaN-free range; snapped to the
// lattice of its cells (as crease_part makes them) unless `snap` is false.
const LineLattice lattice = line_lattice(14.9);
DrapedLineSet walk_lines(int lines, std::uint32_t seed, bool snap = true) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> step(0.0f, 0.3f);
    DrapedLineSet set;
    for (int i = 0; i < lines; ++i) {
        DrapedLine l;
        l.first = std::uint32_t(set.vertices.size());
        l.count = i == 3 ? 1 : 5 + std::uint32_t(rng() % 60);
        l.order = std::uint8_t(1 + rng() % 4);
        float x = 1000.0f + float(rng() % 5000), y = -2000.0f + float(rng() % 5000), flow = 0.0f;
        for (std::uint32_t k = 0; k < l.count; ++k) {
            x += 14.9f + step(rng), y += step(rng) * 14.9f, flow += 1e-4f;
            const float z = 300.0f + 20.0f * std::sin(x * 1e-3f) * std::cos(y * 1e-3f);
            const float nx = 0.02f * std::cos(x * 1e-3f), ny = -0.02f * std::sin(y * 1e-3f);
            set.vertices.push_back({x, y, z, nx, ny, std::sqrt(1.0f - nx * nx - ny * ny), flow});
        }
        set.lines.push_back(l);
    }
    set.vertices[0].nx = -0.0f;
    set.vertices[1].nx = set.vertices[1].ny = set.vertices[1].nz = 0.0f;  // off the surface: no normal
    set.vertices[2].nz = std::nextafter(set.vertices[2].nz, 0.0f);         // not the z its x and y give
    if (snap)
        for (DrapedVertex& v : set.vertices) v = snapped_vertex(v, lattice);
    index_lines(set);
    return set;
}

// Ascending stem ids with gaps (the first not 0, one step of 2^31) and bounds of a tile's stems.
std::vector<std::uint32_t> stem_ids(std::size_t n) {
    std::vector<std::uint32_t> ids;
    for (std::uint32_t i = 0, s = 17; i < n; ++i, s += 1 + 7 * (i % 5)) ids.push_back(i == n - 1 ? s + (1u << 31) : s);
    return ids;
}
std::vector<StemBound> stem_bounds(std::size_t n) {
    std::vector<StemBound> b(n);
    for (std::size_t i = 0; i < n; ++i)
        b[i] = {std::uint16_t(100 + 3 * i), std::uint16_t(65000 - 5 * i), std::uint16_t(120 + 9 * i),
                std::uint16_t(65010 - 5 * i), std::uint16_t(0x4000 + i), std::uint16_t(0x3f00 + 2 * i)};
    b[1] = StemBound{};  // an empty box
    return b;
}

TEST(LineTileFiles, LinesComeBackBitForBitInFewerBytes) {
    const DrapedLineSet set = walk_lines(200, 3);
    const std::vector<std::uint32_t> ids = stem_ids(200);
    const std::vector<StemBound> bounds = stem_bounds(200);
    const std::vector<std::uint8_t> bytes = encode_line_tile(7, lattice, set, ids, bounds);
    TileLines back;
    ASSERT_TRUE(decode_line_tile(bytes.data(), bytes.size(), 7, back));
    ASSERT_EQ(back.lines.vertices.size(), set.vertices.size());
    EXPECT_EQ(std::memcmp(back.lines.vertices.data(), set.vertices.data(), sizeof(DrapedVertex) * set.vertices.size()), 0);
    EXPECT_TRUE(back.lines == set);  // records, boxes, lengths and index as index_lines makes them
    EXPECT_EQ(back.stems, ids);
    EXPECT_EQ(back.bounds, bounds);
    EXPECT_EQ(back.rest, TileRest{});
    // a file of some of its level's stems: what bounds those it leaves out comes back as written
    TileRest rest;
    rest.stems = {3, 5, 1000, 70000};
    rest.bounds = {StemBound{1, 2, 3, 4, 5, 6}, StemBound{7, 8, 9, 10, 11, 12}, StemBound{}, StemBound{0, 0, 65535, 65535, 0x4321, 0x0102}};
    const std::vector<std::uint8_t> some = encode_line_tile(7, lattice, set, ids, bounds, rest);
    TileLines some_back;
    ASSERT_TRUE(decode_line_tile(some.data(), some.size(), 7, some_back));
    EXPECT_EQ(some_back.rest, rest);
    EXPECT_TRUE(some_back.lines == set);
    // the 7 floats of a walk coded in under 6 of their 28 bytes, ids and bounds included (its
    // random turns of a third of a cell a step cost more than a crease's smooth ones)
    EXPECT_LT(double(bytes.size()), 6.0 * double(set.vertices.size()));
    ::testing::Test::RecordProperty("bytes_per_vertex", std::to_string(double(bytes.size()) / set.vertices.size()));
}

TEST(LineTileFiles, DamageAnotherKeyOrACutReadAsAbsent) {
    const DrapedLineSet set = walk_lines(50, 4);
    const std::vector<std::uint32_t> ids = stem_ids(50);
    const std::vector<StemBound> bounds = stem_bounds(50);
    const std::vector<std::uint8_t> bytes = encode_line_tile(7, lattice, set, ids, bounds);
    TileLines back;
    EXPECT_FALSE(decode_line_tile(bytes.data(), bytes.size(), 8, back));
    for (std::size_t cut : {std::size_t(0), std::size_t(7), bytes.size() / 2, bytes.size() - 1})
        EXPECT_FALSE(decode_line_tile(bytes.data(), cut, 7, back)) << cut;
    std::size_t read = 0;
    for (std::size_t at = 0; at < bytes.size(); at += 13) {  // a bit flipped anywhere
        std::vector<std::uint8_t> bad = bytes;
        bad[at] ^= 0x04;
        read += decode_line_tile(bad.data(), bad.size(), 7, back);
    }
    EXPECT_EQ(read, 0u);
    std::vector<std::uint32_t> unsorted = ids;  // ids not ascending: damaged however they were hashed
    std::swap(unsorted[4], unsorted[5]);
    const std::vector<std::uint8_t> disordered = encode_line_tile(7, lattice, set, unsorted, bounds);
    EXPECT_FALSE(decode_line_tile(disordered.data(), disordered.size(), 7, back));

    const test::TempDir dir;
    const std::string path = line_tile_path(dir.file("tiles"), 12, 3);
    EXPECT_FALSE(read_line_tile(path, 7, back));  // absent
    ASSERT_TRUE(write_line_tile(path, 7, lattice, set, ids, bounds));  // the folder made
    ASSERT_TRUE(read_line_tile(path, 7, back));
    EXPECT_TRUE(back.lines == set);
    EXPECT_EQ(back.stems, ids);
    EXPECT_FALSE(read_line_tile(dir.file("tiles"), 7, back));  // a folder, not a file
    EXPECT_FALSE(write_line_tile("/proc/penink-no-such-folder/tile-0-0.pnlt", 7, lattice, set, ids, bounds));
}

TEST(LineTileFiles, LinesOffTheLatticeAreNotWritten) {
    const DrapedLineSet off = walk_lines(20, 5, false), on = walk_lines(20, 5);
    ASSERT_FALSE(off == on);  // the walk's floats are not on the lattice
    const std::vector<std::uint32_t> ids = stem_ids(20);
    const std::vector<StemBound> bounds = stem_bounds(20);
    EXPECT_TRUE(encode_line_tile(7, lattice, off, ids, bounds).empty());
    // one vertex off it is enough; and lines on a lattice are off a finer one's neighbour
    DrapedLineSet one = on;
    one.vertices[30].x = std::nextafter(one.vertices[30].x, 1e9f);
    EXPECT_TRUE(encode_line_tile(7, lattice, one, ids, bounds).empty());
    LineLattice coarser = lattice;
    ++coarser.plan_exp;
    EXPECT_TRUE(encode_line_tile(7, coarser, on, ids, bounds).empty());
    const test::TempDir dir;
    const std::string path = line_tile_path(dir.file("tiles"), 1, 0);
    EXPECT_FALSE(write_line_tile(path, 7, lattice, off, ids, bounds));
    EXPECT_FALSE(std::filesystem::exists(path));
    // a finer lattice holds every vertex of a coarser one: the same lines back
    LineLattice finer = lattice;
    --finer.plan_exp, --finer.z_exp;
    const std::vector<std::uint8_t> bytes = encode_line_tile(7, finer, on, ids, bounds);
    TileLines back;
    ASSERT_TRUE(decode_line_tile(bytes.data(), bytes.size(), 7, back));
    EXPECT_TRUE(back.lines == on);
}

}  // namespace
}  // namespace penink
