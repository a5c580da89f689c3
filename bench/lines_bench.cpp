// Lines-stage throughput: tracing a 2000x2000 silhouette mask (~400k line pixels, a crossing grid
// of 2-px lines) into polylines. Prints ms per trace and pixels per second.
#include <benchmark/benchmark.h>

#include "lines/trace_pixel_lines.hpp"

using namespace penink;

static void BM_TraceCrossingGrid(benchmark::State& state) {
    const int n = 2000;
    PixelMask m{n, n, std::vector<std::uint8_t>(std::size_t(n) * n, 0)};
    std::size_t count = 0;
    auto set = [&](int x, int y) { m.on[std::size_t(y) * n + x] = 1, ++count; };
    for (int y = 10; y < n - 10; y += 20)
        for (int x = 10; x < n - 10; ++x) set(x, y), set(x, y + 1);
    for (int x = 15; x < n - 10; x += 200)
        for (int y = 10; y < n - 10; ++y) set(x, y);
    for (auto _ : state) benchmark::DoNotOptimize(trace_pixel_lines(m, DepthImage{}));
    state.counters["line_pixels"] = double(count);
    state.counters["pixels_per_s"] = benchmark::Counter(double(count), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_TraceCrossingGrid)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
