// Photic extremum line extraction per frame against triangle count (Xie et al. 2007, table 1
// spans 15,744 to 1,984,640 triangles): a bumpy UV sphere (radius 1 + 0.05 sin(7u) sin(5v)) of
// n x n triangles, light at the eye, a new eye position every frame. The per-mesh setup
// (mixed Voronoi areas and hat-function gradients, pel_geometry) is reported once; the counters
// give milliseconds per frame for each step: illumination, gradient, magnitude, D_w, D_w^2,
// extraction, and the number of PEL segments. Also object-space silhouettes per frame.
#include <chrono>
#include <cmath>

#include <benchmark/benchmark.h>

#include "lines/photic_extremum_lines.hpp"
#include "support/test_meshes.hpp"
#include "surface/mesh_normals.hpp"

namespace penink {
namespace {

TriangleMesh bumpy_sphere(int n) {
    return test::uv_sphere(n, 1.0, test::UvLayout::grid,
                           [](double u, double v) { return 0.05 * std::sin(7 * u) * std::sin(5 * v); });
}

void BM_Pel(benchmark::State& state) {
    TriangleMesh m = bumpy_sphere(int(state.range(0)));
    auto t0 = std::chrono::steady_clock::now();
    PelGeometry geom = pel_geometry(m);
    double setup = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    auto normals = mesh_vertex_normals(m, NormalWeighting::area);
    PelTimings sum;
    double segments = 0, frames = 0;
    for (auto _ : state) {
        double a = 0.1 * frames;
        glm::vec3 eye(5 * std::cos(a), 5 * std::sin(a), 1.5f);
        PelResult r = photic_extremum_lines(m, geom, normals, eye, {});
        benchmark::DoNotOptimize(r.segments.data());
        sum.illumination += r.timings.illumination, sum.gradient += r.timings.gradient;
        sum.magnitude += r.timings.magnitude, sum.derivative1 += r.timings.derivative1;
        sum.derivative2 += r.timings.derivative2, sum.extraction += r.timings.extraction;
        sum.total += r.timings.total;
        segments += double(r.segments.size());
        frames += 1;
    }
    state.counters["triangles"] = double(m.triangles.size());
    state.counters["setup_ms"] = setup;
    state.counters["illum_ms"] = sum.illumination / frames;
    state.counters["grad_ms"] = sum.gradient / frames;
    state.counters["mag_ms"] = sum.magnitude / frames;
    state.counters["dw_ms"] = sum.derivative1 / frames;
    state.counters["dw2_ms"] = sum.derivative2 / frames;
    state.counters["extract_ms"] = sum.extraction / frames;
    state.counters["frame_ms"] = sum.total / frames;
    state.counters["segments"] = segments / frames;
}
// n^2 triangles: 15,625 / 62,500 / 250,000 / 1,000,000 / 1,982,464.
BENCHMARK(BM_Pel)->Arg(125)->Arg(250)->Arg(500)->Arg(1000)->Arg(1408)->Unit(benchmark::kMillisecond);

void BM_Silhouettes(benchmark::State& state) {
    TriangleMesh m = bumpy_sphere(int(state.range(0)));
    auto normals = mesh_vertex_normals(m, NormalWeighting::area);
    for (auto _ : state) benchmark::DoNotOptimize(mesh_silhouettes(m, normals, glm::vec3(5, 0, 1.5f)).data());
    state.counters["triangles"] = double(m.triangles.size());
}
BENCHMARK(BM_Silhouettes)->Arg(125)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace penink

BENCHMARK_MAIN();
