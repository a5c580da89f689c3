// Terrain cache (surface/terrain_cache.hpp): CPU of coding and writing a DEM's cache (Write) and
// of opening it (Open) and of opening it and reading, checking and decoding every block
// (ReadWhole), process CPU time
// (the blocks are coded and decoded on every core), with the file's size. The DEM is
// $PENINK_BENCH_DEM, else examples/jacksboro.tif (run from the repository root); e.g. jacksboro
// refined 10 times:
//   PENINK_BENCH_DEM=/tmp/j10.tif build/terrain_cache_bench --benchmark_repetitions=3
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <unistd.h>

#include "input/dem_reader.hpp"
#include "surface/terrain_cache.hpp"

using namespace penink;

namespace {

const StoredTerrain& stored() {
    static const std::unique_ptr<StoredTerrain> t = [] {
        const char* dem = std::getenv("PENINK_BENCH_DEM");
        return std::make_unique<StoredTerrain>(store_terrain(read_dem(dem ? dem : "examples/jacksboro.tif")));
    }();
    return *t;
}

std::string cache_path() {
    return (std::filesystem::temp_directory_path() / ("terrain_cache_bench-" + std::to_string(::getpid()) + ".lod")).string();
}

const TerrainCacheKey key{1, 2, 3, 0, true};

void Write(benchmark::State& state) {
    const StoredTerrain& t = stored();
    const std::string path = cache_path();
    for (auto _ : state) write_terrain_cache(path, t, key);
    state.counters["bytes"] = double(std::filesystem::file_size(path));
    state.counters["bytes_per_node"] = double(std::filesystem::file_size(path)) / double(t.meta.size());
    std::filesystem::remove(path);
}

void ReadWhole(benchmark::State& state) {
    const StoredTerrain& t = stored();
    const std::string path = cache_path();
    write_terrain_cache(path, t, key);
    for (auto _ : state) {
        const std::optional<StoredTerrain> map = read_terrain_cache(path, key);
        if (!map) state.SkipWithError("cache not read");
        else read_whole(*map);
    }
    std::filesystem::remove(path);
}

// Opening alone: the header read and checked, a geographic DEM's projection lattice built.
void Open(benchmark::State& state) {
    const StoredTerrain& t = stored();
    const std::string path = cache_path();
    write_terrain_cache(path, t, key);
    for (auto _ : state)
        if (!read_terrain_cache(path, key)) state.SkipWithError("cache not read");
    std::filesystem::remove(path);
}

}  // namespace

BENCHMARK(Open)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(10);
BENCHMARK(Write)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(3);
BENCHMARK(ReadWhole)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(3);
BENCHMARK_MAIN();
