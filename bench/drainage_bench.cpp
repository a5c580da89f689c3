// Drainage build throughput on synthetic fractal terrain (value noise, 8 octaves) with pits and,
// quantised to 0.25 m, flats: D8 directions + accumulation alone, and the whole build (fill,
// directions, flats, accumulation, basins, branches, divides). Reports cells/s and working
// bytes/cell (per-point arrays) and the process's peak RSS per cell.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <sys/resource.h>

#include <benchmark/benchmark.h>

#include "drainage/drainage_build.hpp"
#include "drainage/least_cost_routing.hpp"
#include "input/dem_reader.hpp"

namespace penink {
namespace {

std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

float lattice(int i, int j, int octave) {
    const std::uint64_t h = splitmix64((std::uint64_t(std::uint32_t(i)) << 32) ^ std::uint32_t(j) ^
                                       (std::uint64_t(octave) << 58));
    return float(h >> 40) / float(1 << 24);  // [0, 1)
}

float value_noise(float x, float y, int octave) {
    const int i = int(std::floor(x)), j = int(std::floor(y));
    float u = x - i, v = y - j;
    u = u * u * (3 - 2 * u), v = v * v * (3 - 2 * v);
    const float a = lattice(i, j, octave), b = lattice(i + 1, j, octave);
    const float c = lattice(i, j + 1, octave), d = lattice(i + 1, j + 1, octave);
    return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
}

DrainageGrid fractal_grid(int n, float quantum) {
    std::vector<float> z(std::size_t(n) * n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            float h = 0, amp = 400, freq = 1.0f / 256;
            for (int o = 0; o < 8; ++o, amp *= 0.5f, freq *= 2) h += amp * value_noise(c * freq, r * freq, o);
            z[std::size_t(r) * n + c] = quantum > 0 ? std::floor(h / quantum) * quantum : h;
        }
    return make_regular_grid(n, n, 10.0, std::move(z));
}

double peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) * 1024.0;
}

void BM_DirectionsAccumulation(benchmark::State& state) {
    const int n = int(state.range(0));
    DrainageGrid g = fractal_grid(n, 0.0f);
    const GridShape s{g.cols, g.rows, g.valid.data()};
    FlowNetwork net;
    for (auto _ : state) {
        const auto dir = d8_directions(g.z, s, g.dx, g.dy);
        accumulate_flow(dir, s, net);
        benchmark::DoNotOptimize(net.acc.data());
    }
    state.counters["cells/s"] = benchmark::Counter(double(g.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["bytes/cell"] = 1.0 + 1.0 + 4.0 + 1.0;  // dir, in-degree, acc, order
}

void BM_WholeBuild(benchmark::State& state) {
    const int n = int(state.range(0));
    DrainageGrid g = fractal_grid(n, 0.25f);
    const double rss0 = peak_rss_bytes();
    DrainageResult res;
    for (auto _ : state) {
        DrainageDb db = drainage_db_from_grid(g, {}, &res);
        benchmark::DoNotOptimize(db.vertices.data());
    }
    state.counters["cells/s"] = benchmark::Counter(double(g.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["bytes/cell"] = double(res.stats.working_bytes) / double(g.size());
    state.counters["rss_growth/cell"] = (peak_rss_bytes() - rss0) / double(g.size());
    state.counters["filled"] = double(res.stats.filled);
    state.counters["basins"] = double(res.stats.basins);
}

void BM_NetworkOnly(benchmark::State& state) {  // fill .. basins, without branch/divide output
    const int n = int(state.range(0));
    DrainageGrid g = fractal_grid(n, 0.25f);
    for (auto _ : state) {
        DrainageResult res = compute_drainage(g);
        benchmark::DoNotOptimize(res.net.acc.data());
    }
    state.counters["cells/s"] = benchmark::Counter(double(g.size()), benchmark::Counter::kIsIterationInvariantRate);
}

// The least-cost search alone (least_cost_routing.hpp) on grid g, with its time per cell.
void time_least_cost(benchmark::State& state, const DrainageGrid& g) {
    const GridShape s{g.cols, g.rows, g.valid.data()};
    for (auto _ : state) {
        const auto dir = least_cost_directions(g.z, s, g.dx, g.dy);
        benchmark::DoNotOptimize(dir.data());
    }
    state.counters["ns/cell"] = benchmark::Counter(double(g.size()) * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                                                             benchmark::Counter::kInvert);
}

// On the unquantised fractal (arg 1 = 0) and on one quantised to 0.25 m (arg 1 = 1: long runs of
// equal elevations).
void BM_LeastCostSearch(benchmark::State& state) {
    time_least_cost(state, fractal_grid(int(state.range(0)), state.range(1) ? 0.25f : 0.0f));
}

// On the DEM named by PENINK_BENCH_DEM at factor 1 (skipped when unset), e.g. a refinement of
// jacksboro: PENINK_BENCH_DEM=/tmp/drape-refined.tif drainage_bench --benchmark_filter=LeastCost
void BM_LeastCostSearchDem(benchmark::State& state) {
    const char* path = std::getenv("PENINK_BENCH_DEM");
    if (!path) return state.SkipWithError("PENINK_BENCH_DEM unset");
    time_least_cost(state, resample_pn(read_dem(path), 1));
}

BENCHMARK(BM_LeastCostSearch)->Args({2048, 0})->Args({2048, 1})->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_LeastCostSearchDem)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_DirectionsAccumulation)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_NetworkOnly)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_WholeBuild)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace penink

BENCHMARK_MAIN();
