// Terrain level of detail (surface/terrain_lod.hpp): build time of the per-node errors and radii,
// and selection time and size of a 1000 x 750 frame, on analytic DEMs of 1 M (1025^2) and 4 M
// (2049^2) nodes, 2 m spacing: Gaussian hills with fractal ripples (smooth, like a real DEM) and
// the same with +-10 m white noise per node (rough at the cell scale: the worst case for the
// error test; there the size floor LodOptions::min_radius_px caps the count).
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>

#include <benchmark/benchmark.h>

#include "core/camera.hpp"
#include "surface/terrain_lod.hpp"
#include "support/synthetic_terrain.hpp"

using namespace penink;

namespace {



double noise(int c, int r) {  // in [-0.5, 0.5)
    std::uint32_t h = std::uint32_t(c) * 2654435761u ^ std::uint32_t(r) * 2246822519u;
    h ^= h >> 15, h *= 2246822519u, h ^= h >> 13;
    return h / 4294967296.0 - 0.5;
}

// side x side nodes; cached per (side, rough).
const Terrain& terrain(int side, bool rough) {
    static std::map<std::pair<int, bool>, std::unique_ptr<Terrain>> cache;
    auto& slot = cache[{side, rough}];
    if (!slot) {
        slot = std::make_unique<Terrain>();
        Terrain& t = *slot;
        t.cols = t.rows = side;
        t.pos.resize(t.size());
        t.valid.assign(t.size(), 1);
        const double s = 4096.0 / (side - 1);  // the same 4 km square at every size
        for (int r = 0; r < side; ++r)
            for (int c = 0; c < side; ++c) {
                const double x = (c - (side - 1) * 0.5) * s, y = ((side - 1) * 0.5 - r) * s;
                t.pos[t.index(c, r)] = glm::vec3(float(x), float(y), float(rough_hills(x, y) + (rough ? 20.0 * noise(c, r) : 0.0)));
            }
    }
    return *slot;
}

Camera framing(const Terrain& t) {
    glm::dvec3 lo, hi;
    terrain_bounds(t, lo, hi);
    return frame_box(lo, hi, {.azimuth = 45.0, .altitude = -30.0, .fov = 40.0, .width = 1000, .height = 750});
}

void BM_BuildTerrainLod(benchmark::State& state) {
    const Terrain& t = terrain(int(state.range(0)), false);
    for (auto _ : state) benchmark::DoNotOptimize(build_terrain_lod(t));
    state.counters["nodes"] = double(t.size());
    state.counters["ns_per_node"] =
        benchmark::Counter(double(t.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BuildTerrainLod)->Arg(1025)->Arg(2049)->Unit(benchmark::kMillisecond);

// range(1): rough (white noise); range(2): min_radius_px.
void BM_SelectLodMesh(benchmark::State& state) {
    const Terrain& t = terrain(int(state.range(0)), state.range(1) != 0);
    const TerrainLod lod = build_terrain_lod(t);
    const Camera cam = framing(t);
    LodOptions o;
    o.min_radius_px = float(state.range(2));
    LodSelection s;
    for (auto _ : state) benchmark::DoNotOptimize(select_lod_mesh(lod, t, cam, o, &s));
    state.counters["triangles"] = double(s.triangles);
    state.counters["tri_per_pixel"] = double(s.triangles) / (1000.0 * 750.0);
}
BENCHMARK(BM_SelectLodMesh)
    ->Args({1025, 0, 0})
    ->Args({2049, 0, 0})
    ->Args({2049, 1, 0})
    ->Args({2049, 1, 2})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
