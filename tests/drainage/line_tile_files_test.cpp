// Tile files of crease lines (src/drainage/line_tile_files.hpp): the lines come back bit for bit,
// coded in fewer bytes than they take in memory; any damage, another key or a cut reads as absent.
#include "drainage/line_tile_files.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "support/temp_dir.hpp"

namespace penink {
namespace {

// Lines like draped creases: a walk of about a cell a step over a smooth surface, with its normals
// and a flow growing downstream; one line of a single vertex, signed zeros and a NaN-free range.
DrapedLineSet walk_lines(int lines, std::uint32_t seed) {
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
    index_lines(set);
    return set;
}

TEST(LineTileFiles, LinesComeBackBitForBitInFewerBytes) {
    const DrapedLineSet set = walk_lines(200, 3);
    const std::vector<std::uint8_t> bytes = encode_line_tile(7, set);
    DrapedLineSet back;
    ASSERT_TRUE(decode_line_tile(bytes.data(), bytes.size(), 7, back));
    ASSERT_EQ(back.vertices.size(), set.vertices.size());
    EXPECT_EQ(std::memcmp(back.vertices.data(), set.vertices.data(), sizeof(DrapedVertex) * set.vertices.size()), 0);
    EXPECT_TRUE(back == set);  // records, boxes, lengths and index as index_lines makes them
    // the 7 floats of a walk coded in under 20 of their 28 bytes
    EXPECT_LT(double(bytes.size()), 20.0 * double(set.vertices.size()));
    ::testing::Test::RecordProperty("bytes_per_vertex", std::to_string(double(bytes.size()) / set.vertices.size()));
}

TEST(LineTileFiles, DamageAnotherKeyOrACutReadAsAbsent) {
    const DrapedLineSet set = walk_lines(50, 4);
    const std::vector<std::uint8_t> bytes = encode_line_tile(7, set);
    DrapedLineSet back;
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

    const test::TempDir dir;
    const std::string path = line_tile_path(dir.file("tiles"), 12, 3);
    EXPECT_FALSE(read_line_tile(path, 7, back));  // absent
    ASSERT_TRUE(write_line_tile(path, 7, set));   // the folder made
    ASSERT_TRUE(read_line_tile(path, 7, back));
    EXPECT_TRUE(back == set);
    EXPECT_FALSE(read_line_tile(dir.file("tiles"), 7, back));  // a folder, not a file
    EXPECT_FALSE(write_line_tile("/proc/penink-no-such-folder/tile-0-0.pnlt", 7, set));
}

}  // namespace
}  // namespace penink
