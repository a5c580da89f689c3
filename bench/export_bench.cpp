// Export throughput: 1 million segments (10k strokes x 100 points, depth 10..1000 m, field-sketch
// style so strokes split into width bands) written as SVG, PS and PDF documents (in memory and
// to a file), and the PNG rasteriser on a 1000 x 1000 drawing with 20k segments.
// Reports seconds per iteration (Google Benchmark) and the output size in MB.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "export/export_drawing.hpp"
#include "export/pdf_writer.hpp"
#include "export/raster_writer.hpp"
#include "export/ps_writer.hpp"
#include "export/svg_writer.hpp"

namespace {

using namespace penink;

// `strokes` wavy polylines of `points` points spread over `size` x `size` pixels, raw splitmix
// bits for positions (deterministic).
Drawing synthetic(int strokes, int points, int size) {
    Drawing d;
    d.width = d.height = size;
    std::uint64_t x = 12345;
    const auto next = [&x] {
        x += 0x9e3779b97f4a7c15ull;
        std::uint64_t z = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    };
    for (int s = 0; s < strokes; ++s) {
        Stroke st;
        const double x0 = next() * size, y0 = next() * size, depth = 10 + 990 * y0 / size;
        for (int i = 0; i < points; ++i) {
            st.points.emplace_back(float(std::fmod(x0 + i * 0.8, size)), float(y0 + 2 * std::sin(i * 0.3)));
            st.depth.push_back(float(depth + i));
        }
        st.kind = "ridge";
        d.layers[1 + s % 6].strokes.push_back(std::move(st));
    }
    return d;
}

// field-sketch widths/opacity by distance (so strokes split into bands), but every stroke kept
// once, so exactly 1,000,000 segments are written.
StyledDrawing make_million() {
    Style style = builtin_style("field-sketch");
    for (LayerStyle& l : style.layers) {
        l.keep_far = 1.0;
        l.repeat = 1;
        l.overshoot = 0.0;
    }
    return style_drawing(synthetic(10000, 101, 4000), style);
}

const StyledDrawing& million() {
    static const StyledDrawing d = make_million();
    return d;
}

template <typename F>
void run(benchmark::State& state, F make) {
    size_t bytes = 0;
    for (auto _ : state) {
        const std::string doc = make(million());
        bytes = doc.size();
        benchmark::DoNotOptimize(doc.data());
    }
    state.counters["MB"] = double(bytes) / 1e6;
}

void BM_SvgDocument(benchmark::State& s) { run(s, [](const StyledDrawing& d) { return svg_document(d, {}); }); }
void BM_PsDocument(benchmark::State& s) { run(s, [](const StyledDrawing& d) { return ps_document(d, {}, false); }); }
void BM_PdfDocument(benchmark::State& s) { run(s, [](const StyledDrawing& d) { return pdf_document(d, {}); }); }

void BM_ExportFile(benchmark::State& state, const char* ext) {
    const std::string path = (std::filesystem::temp_directory_path() / ("penink_bench" + std::string(ext))).string();
    for (auto _ : state) export_drawing(million(), PageOptions{}, path);
    state.counters["MB"] = double(std::filesystem::file_size(path)) / 1e6;
    std::filesystem::remove(path);
}

void BM_RasterisePng(benchmark::State& state) {
    const StyledDrawing d = style_drawing(synthetic(200, 101, 1000), builtin_style("technical"));
    for (auto _ : state) {
        RgbImage img = rasterise(d, raster_transform(d, PageOptions{}));
        benchmark::DoNotOptimize(img.rgb.data());
    }
    state.counters["segments"] = 20000;
}

}  // namespace

BENCHMARK(BM_SvgDocument)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PsDocument)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdfDocument)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ExportFile, svg, ".svg")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ExportFile, ps, ".ps")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ExportFile, pdf, ".pdf")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RasterisePng)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
