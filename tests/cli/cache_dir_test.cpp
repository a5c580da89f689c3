// Caches from the command line: --cache-dir and [cache] dir say where they go (named after the
// DEM and a hash of its path; nothing beside the DEM), -v names each with its size; a damaged
// terrain cache or drainage database is rebuilt and the drawing is the clean one, byte for byte;
// a FIFO where a cache would be is neither read (no blocking) nor replaced, with one warning.
// Odd DEMs: a plane draws its outline and no creases nor hachures, also with denormal heights; a
// plane under a sea level draws the water (the default camera stands above it); a long thin DEM
// whose pyramid would not fit memory is refused with one line; tiny cells draw.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <regex>
#include <sstream>

#include "cli_support.hpp"

using namespace penink::test;
namespace fs = std::filesystem;

namespace {

const std::string size_args = " --width 300 --height 225";

std::vector<fs::path> files_ending(const fs::path& dir, const std::string& ext) {
    std::vector<fs::path> out;
    for (auto& e : fs::directory_iterator(dir))
        if (e.path().string().size() > ext.size() &&
            e.path().string().compare(e.path().string().size() - ext.size(), ext.size(), ext) == 0)
            out.push_back(e.path());
    return out;
}

// Paths in a layer group of an SVG, by the layer's id.
std::size_t layer_paths(const std::string& svg, const std::string& layer) {
    const std::size_t at = svg.find("id=\"" + layer + "\"");
    if (at == std::string::npos) return 0;
    const std::size_t end = svg.find("</g>", at);  // layers hold no groups of their own here
    const std::string part = svg.substr(at, end == std::string::npos ? std::string::npos : end - at);
    std::size_t n = 0;
    for (std::size_t p = part.find("<path"); p != std::string::npos; p = part.find("<path", p + 1)) ++n;
    return n;
}

std::string plane(int n, const std::string& height) {
    std::ostringstream s;
    s << "ncols " << n << "\nnrows " << n << "\nxllcorner 0\nyllcorner 0\ncellsize 10\n";
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) s << height << ' ';
        s << '\n';
    }
    return s.str();
}

}  // namespace

TEST(CacheDir, CommandLineAndSceneFolders) {
    const auto dir = fresh_dir("cache_dir");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    const RunResult r = run_penink("render volcano.asc -o a.svg -v --cache-dir caches" + size_args, dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(files_ending(dir, ".dv").empty() && files_ending(dir, ".lod").empty()) << "a cache beside the DEM";
    const auto dv = files_ending(dir / "caches", ".dv"), lod = files_ending(dir / "caches", ".lod");
    ASSERT_EQ(dv.size(), 1u);
    ASSERT_EQ(lod.size(), 1u);
    const std::string name = dv[0].filename().string();
    EXPECT_TRUE(std::regex_match(name, std::regex("volcano\\.asc-[0-9a-f]{16}\\.dv"))) << name;
    EXPECT_EQ(lod[0].filename().string(), name.substr(0, name.size() - 3) + ".lod");
    // the crease tiles the render built beside the database in the cache folder, none beside the DEM
    EXPECT_TRUE(fs::is_directory(dir / "caches" / (name + ".tiles")));
    EXPECT_FALSE(files_ending(dir / "caches" / (name + ".tiles"), ".pnlt").empty());
    EXPECT_FALSE(fs::exists(dir / "volcano.asc.dv.tiles"));
    EXPECT_TRUE(std::regex_search(r.output, std::regex("tile files read, [1-9][0-9]* written"))) << r.output;
    // -v: each cache with its size
    EXPECT_NE(r.output.find("penink: drainage: wrote caches/" + name + " ("), std::string::npos) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("penink: terrain: wrote caches/volcano\\.asc-[0-9a-f]{16}\\.lod "
                                                       "\\([0-9]+ KiB, [0-9]+ ms\\)")))
        << r.output;
    const RunResult again = run_penink("render volcano.asc -o b.svg -v --cache-dir caches" + size_args, dir);
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_NE(again.output.find("penink: drainage: using cached caches/" + name + " ("), std::string::npos) << again.output;
    EXPECT_NE(again.output.find("penink: terrain: using cached caches/" + name.substr(0, name.size() - 3) + ".lod ("),
              std::string::npos)
        << again.output;
    EXPECT_EQ(read_text(dir / "a.svg"), read_text(dir / "b.svg"));
    EXPECT_TRUE(std::regex_search(again.output, std::regex("[1-9][0-9]* tile files read, 0 written"))) << again.output;

    fs::create_directories(dir / "scene");
    write_text(dir / "scene" / "v.toml", "[terrain]\ndem = \"../volcano.asc\"\n[cache]\ndir = \"cc\"\n");
    const RunResult s = run_penink("render scene/v.toml -o c.svg" + size_args, dir);
    ASSERT_EQ(s.code, 0) << s.output;
    EXPECT_EQ(files_ending(dir / "scene" / "cc", ".dv").size(), 1u);  // relative to the scene file
    EXPECT_EQ(files_ending(dir / "scene" / "cc", ".lod").size(), 1u);
    const RunResult d = run_penink("drainage volcano.asc --cache-dir dcache -q", dir);
    ASSERT_EQ(d.code, 0) << d.output;
    EXPECT_EQ(files_ending(dir / "dcache", ".dv").size(), 1u);
    EXPECT_EQ(files_ending(dir / "dcache", ".lod").size(), 1u);
    EXPECT_TRUE(files_ending(dir, ".dv").empty());
    fs::remove_all(dir);
}

// Bytes flipped or cut in either cache: found as the damaged block is read, the cache rebuilt,
// the drawing the clean one.
TEST(CacheDir, DamagedCachesAreRebuiltNeverDrawn) {
    const auto dir = fresh_dir("cache_damaged");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    ASSERT_EQ(run_penink("render volcano.asc -o clean.svg" + size_args, dir).code, 0);
    const std::string clean = read_text(dir / "clean.svg");
    const std::string lod = read_text(dir / "volcano.asc.lod"), dv = read_text(dir / "volcano.asc.dv");
    ASSERT_GT(lod.size(), 5000u);  // coded (terrain_cache.hpp): 9 kB
    ASSERT_GT(dv.size(), 100000u);  // the ridges and the creases' source (drainage_db.cpp): 0.64 MB
    std::uint64_t lines_at = 0;  // the lines part, which a render reads (dv_format.hpp)
    std::memcpy(&lines_at, dv.data() + 24, 8);
    ASSERT_LT(lines_at, dv.size());
    // the terrain cache's arrays (terrain_cache.hpp): offsets of pos, valid, error, lattice, the
    // coarse nodes, the edge columns and the UTM lattice after the 232 bytes of magic, version,
    // length, key, grid and pyramid, then the length
    std::uint64_t at[8];
    std::memcpy(at, lod.data() + 232, sizeof at);
    ASSERT_EQ(at[7], lod.size());
    ASSERT_LT(at[3], at[4]);  // a projected DEM: x, y derived, a node lattice kept
    ASSERT_EQ(at[6], at[7]);  // (and no UTM lattice: its x, y are affine)
    int k = 0;
    // what a whole view reads of the terrain cache: the middle of the nodes' heights, of the
    // pyramid's errors, and the node lattice's end; the lines part's vertices (middle, three
    // quarters: read or not, as the view needs them) and its index's checksum at the end (the
    // part's last 16 bytes: the index's, then the part's)
    const std::uint64_t in_lod[3] = {(at[0] + at[1]) / 2, (at[2] + at[3]) / 2, at[4] - 1};
    for (const double where : {0.5, 0.75, 0.999}) {
        std::string l = lod, d = dv;
        l[std::size_t(in_lod[k])] ^= 0x40;
        d[where > 0.99 ? d.size() - 12 : std::size_t(double(lines_at) + where * double(d.size() - lines_at))] ^= 0x40;
        write_text(dir / "volcano.asc.lod", l);
        write_text(dir / "volcano.asc.dv", d);
        const std::string out = std::string("d").append(std::to_string(k++)).append(".svg");
        const RunResult r = run_penink("render volcano.asc -o " + out + " -v" + size_args, dir);
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("penink: terrain: volcano.asc.lod: damaged terrain cache (block checksum); building"),
                  std::string::npos)
            << where << "\n" << r.output;
        if (where > 0.99) {  // the index: found when it is read
            EXPECT_NE(r.output.find("volcano.asc.dv: drainage database checksum mismatch (file corrupt); rebuilding"),
                      std::string::npos)
                << r.output;
        }
        EXPECT_EQ(read_text(dir / out), clean) << where;
        EXPECT_EQ(read_text(dir / "volcano.asc.lod"), lod) << "rebuilt as it was";
    }
    write_text(dir / "volcano.asc.lod", lod.substr(0, lod.size() / 2));  // cut
    const RunResult r = run_penink("render volcano.asc -o cut.svg -v" + size_args, dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: terrain: volcano.asc.lod: damaged terrain cache (lengths); building"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(read_text(dir / "cut.svg"), clean);
    fs::remove_all(dir);
}

TEST(CacheDir, FifoWhereACacheWouldBeIsIgnoredWithAWarning) {
    const auto dir = fresh_dir("cache_fifo");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    ASSERT_EQ(run_penink("render volcano.asc -o clean.svg" + size_args, dir).code, 0);
    fs::remove(dir / "volcano.asc.lod");
    fs::remove(dir / "volcano.asc.dv");
    ASSERT_EQ(::mkfifo((dir / "volcano.asc.lod").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((dir / "volcano.asc.dv").c_str(), 0600), 0);
    const RunResult r = run_penink("", dir, "timeout 120 '" PENINK_BINARY_PATH "' render volcano.asc -o f.svg" + size_args);
    ASSERT_EQ(r.code, 0) << r.output;  // 124 if it blocked on a FIFO
    EXPECT_EQ(r.output,
              "penink: warning: terrain: volcano.asc.lod: not a regular file; the terrain cache is neither read nor "
              "written (built in memory)\n"
              "penink: warning: drainage: volcano.asc.dv: not a regular file; the drainage cache is neither read nor "
              "written (the database is built in memory)\n");
    EXPECT_EQ(read_text(dir / "f.svg"), read_text(dir / "clean.svg"));
    EXPECT_TRUE(fs::is_fifo(dir / "volcano.asc.lod"));
    EXPECT_TRUE(fs::is_fifo(dir / "volcano.asc.dv"));
    fs::remove_all(dir);
}

TEST(OddDems, PlaneDrawsItsOutlineAndNoCreasesNorHachures) {
    const auto dir = fresh_dir("odd_plane");
    write_text(dir / "flat.asc", plane(60, "100"));
    write_text(dir / "denormal.asc", plane(60, "1e-310"));  // float64 denormals
    for (const std::string dem : {"flat.asc", "denormal.asc"}) {
        const RunResult r = run_penink("render " + dem + " -o " + dem + ".svg" + size_args, dir);
        ASSERT_EQ(r.code, 0) << r.output;
        const std::string svg = read_text(dir / (dem + ".svg"));
        EXPECT_EQ(layer_paths(svg, "creases"), 0u) << dem;
        EXPECT_EQ(layer_paths(svg, "ridges"), 0u) << dem;
        EXPECT_EQ(layer_paths(svg, "hachures"), 0u) << dem;
        EXPECT_GE(layer_paths(svg, "silhouettes"), 1u) << dem;  // the outline
    }
    // under a sea level far above it, with no camera: framed above the water, which it draws
    write_text(dir / "sea.toml", "[terrain]\ndem = \"flat.asc\"\nsea_level = 5000\n");
    const RunResult r = run_penink("render sea.toml -o sea.svg" + size_args, dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output, "");
    EXPECT_GE(layer_paths(read_text(dir / "sea.svg"), "silhouettes"), 1u);
    fs::remove_all(dir);
}

TEST(OddDems, LongThinDemBeyondMemoryIsRefusedWithOneLine) {
    const auto dir = fresh_dir("odd_long");
    std::ostringstream s;
    s << "ncols 1000000\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n";
    for (int r = 0; r < 2; ++r) {
        for (int c = 0; c < 1000000; ++c) s << (c % 13) << ' ';
        s << '\n';
    }
    write_text(dir / "long.asc", s.str());
    const RunResult r = run_penink("render long.asc -o long.svg" + size_args, dir);
    EXPECT_EQ(r.code, 2) << r.output;
    // 2^20 + 1 nodes a side: the pyramid's strips alone hold a row of 4 bytes a node every 32
    // rows, 128 GiB, more than these machines have
    EXPECT_EQ(r.output.rfind("penink: surface: long.asc: building the terrain cache of the DEM's 1000000x2 nodes "
                             "(1048577^2 padded nodes) would need about ",
                             0),
              0u)
        << r.output;
    EXPECT_NE(r.output.find(" GiB of memory, "), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1);
    EXPECT_EQ(file_count(dir), 1u) << "an output or cache was left";
    fs::remove_all(dir);
}

TEST(OddDems, TinyCellsDraw) {
    const auto dir = fresh_dir("odd_tiny");
    std::ostringstream s;
    s << "ncols 40\nnrows 40\nxllcorner 10\nyllcorner 45\ncellsize 1e-9\n";
    for (int r = 0; r < 40; ++r) {
        for (int c = 0; c < 40; ++c) s << (r * c) % 7 << ' ';
        s << '\n';
    }
    write_text(dir / "tiny.asc", s.str());  // metres: 1 nm cells
    write_text(dir / "tinydeg.asc", s.str());
    write_text(dir / "tinydeg.prj", "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
                                    "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]]");  // 1e-9 degrees
    for (const std::string dem : {"tiny.asc", "tinydeg.asc"}) {
        const RunResult r = run_penink("render " + dem + " -o " + dem + ".svg" + size_args, dir);
        ASSERT_EQ(r.code, 0) << r.output;
        const std::string svg = read_text(dir / (dem + ".svg"));
        EXPECT_GE(layer_paths(svg, "silhouettes"), 1u) << dem;
        EXPECT_GE(layer_paths(svg, "surface"), 1u) << dem;
    }
    fs::remove_all(dir);
}
