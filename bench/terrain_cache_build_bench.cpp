// Building a DEM's terrain cache alone (scene/terrain_view.hpp, open_stored_terrain with no cache
// present: read the DEM, build the pyramid, code and write the .lod, open it): wall time per
// build, and, run under /usr/bin/time -v, the build's peak resident memory (the process holds
// nothing else). The DEM is $PENINK_BENCH_DEM, else examples/jacksboro.tif (run from the
// repository root); the cache goes to a fresh folder under the temporary directory, removed after
// ($PENINK_BENCH_KEEP: that folder instead, emptied first and kept, to compare the files built).
// -v lines (read, pyramid, written) on stderr. E.g. jacksboro refined 29 times:
//   PENINK_BENCH_DEM=/tmp/j29.tif /usr/bin/time -v build/terrain_cache_build_bench --benchmark_repetitions=1
#include <cstdlib>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>
#include <unistd.h>

#include "core/log.hpp"
#include "scene/terrain_view.hpp"

using namespace penink;

namespace {

void Build(benchmark::State& state) {
    const char* env = std::getenv("PENINK_BENCH_DEM");
    const std::string dem = std::filesystem::absolute(env ? env : "examples/jacksboro.tif").string();
    const char* keep = std::getenv("PENINK_BENCH_KEEP");
    const std::filesystem::path dir =
        keep ? std::filesystem::path(keep)
             : std::filesystem::temp_directory_path() / ("terrain_cache_build_bench-" + std::to_string(::getpid()));
    Log log;
    log.verbose = true;
    for (auto _ : state) {
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
        const StoredTerrain t = open_stored_terrain(dem, log, dir.string());
        benchmark::DoNotOptimize(t.lod.levels);
    }
    std::uintmax_t bytes = 0;
    for (const auto& f : std::filesystem::directory_iterator(dir))
        if (f.path().extension() == ".lod") bytes = f.file_size();
    state.counters["lod_MiB"] = double(bytes) / (1024.0 * 1024.0);
    if (!keep) std::filesystem::remove_all(dir);
}
BENCHMARK(Build)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
