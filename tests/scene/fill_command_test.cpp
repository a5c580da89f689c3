// `penink fill`: the filled DEM written a band of rows at a time is the drainage build's
// Priority-Flood fill of the whole DEM bit for bit (nodata NaN), georeferenced like the DEM; a
// filled DEM fills to itself; bad outputs and a memory budget too small are refused with one line
// and leave no file.
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include "drainage/priority_flood.hpp"
#include "input/dem_reader.hpp"
#include "scene/fill_command.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;

struct Band {
    int w = 0, h = 0;
    double gt[6] = {};
    std::vector<float> z;
};

Band read_filled(const fs::path& p) {
    Band b;
    GDALAllRegister();
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(p.string().c_str(), GA_ReadOnly));
    if (!ds) return b;
    b.w = ds->GetRasterXSize(), b.h = ds->GetRasterYSize();
    ds->GetGeoTransform(b.gt);
    b.z.resize(std::size_t(b.w) * b.h);
    if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, b.w, b.h, b.z.data(), b.w, b.h, GDT_Float32, 0, 0) != CE_None)
        b.z.clear();
    GDALClose(ds);
    return b;
}

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("penink_fill_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// An ASCII grid with pits, a flat-floored basin and a block of nodata inside (whose rim cells are
// outlets), 70 x 53 nodes of 10 m.
std::string grid_with_nodata(const fs::path& d) {
    const fs::path p = d / "holes.asc";
    std::ofstream out(p);
    out << "ncols 70\nnrows 53\nxllcorner 500000\nyllcorner 4000000\ncellsize 10\nNODATA_value -9999\n";
    for (int r = 0; r < 53; ++r) {
        for (int c = 0; c < 70; ++c) {
            double z = 100.0 + 10.0 * std::sin(c / 5.0) * std::cos(r / 7.0) + 0.2 * c;
            if ((c * 7 + r * 13) % 11 == 0) z -= 5.0;                  // pits
            if (r >= 30 && r < 40 && c >= 10 && c < 25) z = 90.0;      // a basin floor
            if (r >= 20 && r < 26 && c >= 40 && c < 52) z = -9999.0;   // nodata
            out << z << (c + 1 < 70 ? " " : "\n");
        }
    }
    return p.string();
}

TEST(FillCommand, FilledDemIsTheWholeFillBitForBit) {
    const fs::path d = scratch("same");
    const std::string holes = grid_with_nodata(d);
    for (const std::string& dem : {std::string(PENINK_SOURCE_DIR "/examples/jacksboro.tif"),
                                   std::string(PENINK_SOURCE_DIR "/examples/volcano.asc"), holes}) {
        const std::string name = fs::path(dem).filename().string();
        DemOptions o;
        o.heights_only = true, o.no_xy = true;
        const Terrain t = read_dem(dem, o);
        std::vector<float> expected = t.z;
        std::vector<std::uint8_t> flags;
        CellWords orig;
        const FillStats whole = priority_flood_fill(expected, {t.cols, t.rows, t.valid.data()}, flags, orig);
        EXPECT_GT(whole.raised, 10u) << name;
        std::size_t nodata = 0;
        for (const int band_rows : {0, 16, 37}) {
            FillCommand cmd;
            cmd.dem = dem, cmd.output = (d / "filled.tif").string(), cmd.band_rows = band_rows;
            std::ostringstream log;
            ASSERT_EQ(run_fill_command(cmd, log), 0) << log.str();
            EXPECT_NE(log.str().find(std::to_string(whole.raised) + " raised"), std::string::npos) << log.str();
            const Band b = read_filled(cmd.output);
            ASSERT_EQ(b.w, t.cols);
            ASSERT_EQ(b.h, t.rows);
            ASSERT_EQ(b.z.size(), t.size());
            for (std::size_t i = 0; i < t.size(); ++i) {
                if (!t.valid[i]) {
                    ASSERT_TRUE(std::isnan(b.z[i])) << name << " cell " << i;
                    ++nodata;
                    continue;
                }
                ASSERT_EQ(std::bit_cast<std::uint32_t>(b.z[i]), std::bit_cast<std::uint32_t>(expected[i]))
                    << name << " band rows " << band_rows << " cell " << i;
            }
            // north-up DEMs: the same geotransform
            GDALDataset* src = static_cast<GDALDataset*>(GDALOpen(dem.c_str(), GA_ReadOnly));
            ASSERT_NE(src, nullptr);
            double gt[6];
            src->GetGeoTransform(gt);
            GDALClose(src);
            for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(b.gt[k], gt[k]) << name << " " << k;
        }
        if (dem == holes) {
            EXPECT_EQ(nodata, 3u * 6 * 12);
        }
    }
    {  // a filled DEM is filled already: filling it again changes no height
        FillCommand once, twice;
        once.dem = PENINK_SOURCE_DIR "/examples/jacksboro.tif", once.output = (d / "once.tif").string();
        twice.dem = once.output, twice.output = (d / "twice.tif").string(), twice.band_rows = 16;
        std::ostringstream log;
        ASSERT_EQ(run_fill_command(once, log), 0) << log.str();
        ASSERT_EQ(run_fill_command(twice, log), 0) << log.str();
        EXPECT_NE(log.str().find(" 0 raised"), std::string::npos) << log.str();
        const Band a = read_filled(once.output), b = read_filled(twice.output);
        ASSERT_FALSE(a.z.empty());
        EXPECT_EQ(a.z, b.z);
    }
    fs::remove_all(d);
}

TEST(FillCommand, RefusesWithOneLineAndLeavesNoFile) {
    const fs::path d = scratch("refuse");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", d / "volcano.asc");
    const auto before = fs::file_size(d / "volcano.asc");
    auto run = [&](FillCommand cmd) {
        std::ostringstream log;
        const int code = run_fill_command(cmd, log);
        return std::make_pair(code, log.str());
    };
    FillCommand c;
    c.dem = (d / "volcano.asc").string();
    c.output = c.dem;  // the DEM itself
    auto [code, line] = run(c);
    EXPECT_EQ(code, 2);
    EXPECT_NE(line.find("penink: fill: " + c.dem + ": is the DEM"), std::string::npos) << line;
    EXPECT_EQ(fs::file_size(d / "volcano.asc"), before);
    c.output = (d / "missing" / "filled.tif").string();  // no such folder
    std::tie(code, line) = run(c);
    EXPECT_EQ(code, 2);
    EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
    c.output = (d / "filled.tif").string(), c.max_memory = 1000;  // not one band fits
    std::tie(code, line) = run(c);
    EXPECT_EQ(code, 2);
    EXPECT_NE(line.find("would need about"), std::string::npos) << line;
    c.max_memory = 0, c.dem = (d / "none.asc").string();
    std::tie(code, line) = run(c);
    EXPECT_EQ(code, 2);
    EXPECT_NE(line.find("no such file"), std::string::npos) << line;
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++files;
    EXPECT_EQ(files, 1u);  // the DEM alone: no output, no temporary
    fs::remove_all(d);
}

// The automatic band height: about 4 M cells in whole strips, fewer rows where memory is short,
// none when not one strip's band fits.
TEST(FillCommand, BandRowsFollowTheBudget) {
    EXPECT_EQ(fill_command_band_rows(10812, 10812, 2, std::uint64_t(8) << 30), 384);  // 4 M cells / 10812 in strips of 16
    EXPECT_EQ(fill_command_band_rows(100, 50, 2, std::uint64_t(8) << 30), 64);        // the grid in one band of whole strips
    const int tight = fill_command_band_rows(10812, 10812, 2, std::uint64_t(300) << 20);
    EXPECT_GE(tight, 16);
    EXPECT_LT(tight, 384);
    EXPECT_EQ(tight % 16, 0);
    EXPECT_EQ(fill_command_band_rows(10812, 10812, 2, 1 << 20), 0);
}

}  // namespace
}  // namespace penink
