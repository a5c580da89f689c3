// Flow accumulation a band of rows at a time (drainage/tiled_accumulation.hpp) against the whole
// grid's (flow_network.hpp accumulate_flow), on D8 directions of a DEM's heights (d8.hpp, cells of
// 1 x 1: for the scale, not a drainage model; pits and flats are outlets). The DEM is
// $PENINK_BENCH_DEM (say the filled DEM `penink fill` writes), else examples/jacksboro.tif; bands
// of $PENINK_BENCH_BAND_ROWS rows (default 112). Tiled reads the DEM by rows (input/dem_reader.hpp
// DemRows), each band's directions from its rows and one more on each side, so it holds a few
// bands and the perimeter's graph; Whole reads it all (skipped over 300 M cells). Both report the
// sum of the accumulations (counter "sum": equal where they agree) and, under /usr/bin/time -v,
// the peak memory of the one that ran (--benchmark_filter). E.g. a 1.0 G-cell DEM:
//   penink fill /tmp/j85.tif -o /tmp/f85.tif
//   PENINK_BENCH_DEM=/tmp/f85.tif /usr/bin/time -v build/tiled_accumulation_bench --benchmark_filter=Tiled
#include <cstdlib>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "drainage/d8.hpp"
#include "drainage/flow_network.hpp"
#include "drainage/tiled_accumulation.hpp"
#include "input/dem_reader.hpp"

using namespace penink;

namespace {

std::string bench_dem() {
    const char* env = std::getenv("PENINK_BENCH_DEM");
    return std::filesystem::absolute(env ? env : "examples/jacksboro.tif").string();
}

DemOptions heights() {
    DemOptions o;
    o.heights_only = true, o.no_xy = true;
    return o;
}

void Tiled(benchmark::State& state) {
    const char* rows_env = std::getenv("PENINK_BENCH_BAND_ROWS");
    const int band_rows = rows_env ? std::max(1, std::atoi(rows_env)) : 112;
    limit_gdal_block_cache(std::uint64_t(64) << 20);
    for (auto _ : state) {
        DemRows dem(bench_dem(), heights(), 0, false);
        const int cols = dem.meta().cols, rows = dem.meta().rows;
        std::vector<float> z;
        std::vector<std::uint8_t> valid;
        // the directions of rows [y0, y1): D8 of those rows and one more on each side
        const DirRowReader read = [&](int y0, int y1, std::uint8_t* dir, std::uint8_t* ok) {
            const int w0 = std::max(0, y0 - 1), w1 = std::min(rows, y1 + 1);
            z.resize(std::size_t(w1 - w0) * cols), valid.resize(z.size());
            dem.rows(w0, w1, z.data(), valid.data());
            const std::vector<std::uint8_t> d = d8_directions(z, {cols, w1 - w0, valid.data()}, 1.0, 1.0, nullptr, false);
            const std::size_t at = std::size_t(y0 - w0) * cols, n = std::size_t(y1 - y0) * cols;
            std::copy(d.begin() + std::ptrdiff_t(at), d.begin() + std::ptrdiff_t(at + n), dir);
            std::copy(valid.begin() + std::ptrdiff_t(at), valid.begin() + std::ptrdiff_t(at + n), ok);
        };
        double sum = 0;
        tiled_accumulation({cols, rows, band_rows}, read, [&](int y0, int y1, const std::uint32_t* acc) {
            for (std::size_t i = 0; i < std::size_t(y1 - y0) * cols; ++i) sum += acc[i];
        });
        state.counters["sum"] = sum;
        state.counters["cells"] = double(cols) * rows;
    }
}
BENCHMARK(Tiled)->Unit(benchmark::kSecond)->Iterations(1);

void Whole(benchmark::State& state) {
    for (auto _ : state) {
        DemRows dem(bench_dem(), heights(), 0, false);
        const int cols = dem.meta().cols, rows = dem.meta().rows;
        if (double(cols) * rows > 3e8) {
            state.SkipWithError("over 300 M cells: not held whole");
            return;
        }
        std::vector<float> z(std::size_t(cols) * rows);
        std::vector<std::uint8_t> valid(z.size());
        dem.rows(0, rows, z.data(), valid.data());
        const GridShape g{cols, rows, valid.data()};
        FlowNetwork net;
        accumulate_flow(d8_directions(z, g, 1.0, 1.0, nullptr, false), g, net);
        double sum = 0;
        for (const std::uint32_t a : net.acc) sum += a;
        state.counters["sum"] = sum;
        state.counters["cells"] = double(cols) * rows;
    }
}
BENCHMARK(Whole)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
