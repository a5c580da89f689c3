// Memory a terrain drawing needs, estimated from the DEM's header before anything is read: what
// building its caches holds (the terrain cache's build, streamed: cache_build_estimate.hpp; the
// drainage build at the automatic factor where the scene draws creases or ridges,
// drainage/drainage_memory.hpp) and, with a sea level, the pyramid rebuilt for it, against a
// budget. A frame drawn from the caches reads what its image needs and holds less.
#pragma once
#include <cstdint>

#include "scene/scene.hpp"

namespace penink {

// A terrain held whole in memory (DEM read, pyramid, level-of-detail mesh): the terrain cache's
// fallback where it cannot be streamed (terrain_view.cpp).
constexpr double render_bytes_per_node = 64.0;
// The image's buffers (GPU targets, read-back, line masks, raster output): 31.5 B a pixel
// measured (peak RSS of `render volcano.asc -o m.png` at 1024² and 3072²: 250 MB and 508 MB).
constexpr double render_bytes_per_pixel = 32.0;
// A scene with a sea level rebuilds the pyramid for it (terrain_view.hpp): heights, flags,
// errors and lod_errors' strips while it builds, counted over the padded square (an upper bound:
// the errors are kept for the DEM's nodes alone).
constexpr double water_lod_bytes_per_padded_node = 10.0;
// A pyramid held in memory holds a float error per node (terrain_lod.hpp; its build holds the
// strips of lod_errors_bytes besides).
constexpr double lod_bytes_per_node = 4.0;

// Throws Error("drainage", DEM, "the drainage grid of the creases and ridges at factor F (CxR
// points) would need about N of memory, B available (--max-memory); without creases and ridges
// ([creases] and [ridges] enabled = false) the drawing needs about M") when the scene would fit
// without the drainage build, Error("input", DEM, "drawing the DEM's WxH nodes would need about N
// of memory, B available (--max-memory)") when a terrain scene would not fit memory_budget(max_memory) otherwise, and
// Error("scene", file, "drawing a WxH image [of the DEM's CxR nodes] would need ...") when the
// image's buffers (render_bytes_per_pixel) with the DEM's would not (any scene, a mesh's too); also
// the DEM reader's opening errors (read_dem_size). A mesh scene is not checked, nor, without
// --max-memory, a DEM file under check_memory_from_bytes: opening it costs 5-20 ms of a 0.2 s
// render, and the reader itself refuses a DEM whose read alone would not fit the memory available
// (a small file declaring a huge grid included).
constexpr std::uint64_t check_memory_from_bytes = std::uint64_t(8) << 20;
void check_scene_memory(const Scene& scene, std::uint64_t max_memory);

// What check_scene_memory counts for drawing a cols x rows DEM from its caches: the terrain
// cache's build, with a sea level the pyramid rebuilt for it, and the image's buffers (no drainage
// build). A render's later builds (crease tiles) are checked on top of it.
double scene_frame_bytes(const Scene& scene, int cols, int rows);

}  // namespace penink
