// The timing tables of `penink batch`: per-frame times (ms) of a flight or orbit turned into the
// papers' tables. Terrains: Mower, "Concurrent Drainage Network Rendering", Tables 3 (mean ms per
// pass and frame) and 4 (frame rates): every fps is the mean over the frames of 1000 / t_i (t_i
// in ms), not 1000 / mean t; TOTAL is the paper's sum of its passes with LAY, the composite pass
// (penink: finish, style and export of the frame's files), included; the warm-up frames (the
// first three by default, as the paper) are a row of their own, outside the other row's means.
// Meshes: Potter et al., "NPR-Style 3D Line Textures", Table 1 (frame times of walk-throughs of
// models), split into penink's mesh steps. Column mapping: docs/timings.md.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "scene/frame_source.hpp"

namespace penink {

struct FrameTiming {
    int frame = 0;          // 1-based, in the whole flight
    bool warmup = false;
    PassTimings times;      // GPU passes, ms
    MeshLineTimings lines;  // a mesh frame's object-space steps, ms
    double trace = 0;       // CPU: images -> polylines (a mesh: every object-space line), ms
    double finish = 0;      // CPU: sketch, thinning, plotter order (finish_drawing), ms
    double write = 0;       // CPU: style and export of the frame's files, ms
    double total = 0;       // wall time of the whole frame, ms
    double lay() const { return finish + write; }  // the paper's LAY
};

// The creases paper's TOTAL of one frame: TFT + AFT + DM + SIL + RIDGES + LAY (ms).
double passes_total(const FrameTiming& f);

struct TimingRow {
    std::string frames;  // "warm-up" or "after warm-up"
    int n = 0;
    FrameTiming mean;    // every time the mean over the row's frames (frame, warmup unused)
    // Means over the row's frames of 1000 / t_i; a frame whose t_i is 0 (pass not run) is left
    // out of that mean; 0 when no frame ran it.
    double crease_fps = 0;  // t = TFT + DM (the crease passes)
    double silh_fps = 0;    // t = TFT + AFT + SIL (the silhouette passes)
    double total_fps = 0;   // t = passes_total
    double frame_fps = 0;   // t = the whole frame's wall time (penink's frame rate)
};

// The warm-up row (frames flagged warmup) then the other, each only when it has frames.
std::vector<TimingRow> timing_rows(const std::vector<FrameTiming>& frames);

// What a run was, for the tables' heading.
struct BatchSummary {
    std::string machine, scene;
    int width = 0, height = 0, warmup = 0;
    bool mesh = false;
    std::size_t cells = 0, dem_cells = 0;  // a terrain: DEM cells modelled / in the DEM
    std::size_t triangles = 0;             // a mesh: its triangles after subdivision
    double setup_s = 0;
};

// CSV, one row per frame. Terrain: "frame,warmup,tft,aft,dm,sil,ridges,lay,readback,trace,total";
// mesh: "frame,warmup,tft,aft,sil,readback,normals,pel_geometry,pel,silhouettes,features,textures,
// visibility,lines,sketch,export,total".
std::string timings_csv(const std::vector<FrameTiming>& frames, bool mesh);

// Markdown: the run's context and the tables (terrain: Tables 3 and 4; mesh: Table 1).
std::string timings_markdown(const std::vector<FrameTiming>& frames, const BatchSummary& summary);

}  // namespace penink
