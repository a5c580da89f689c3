// `penink batch`'s frames and timing tables (batch_run.hpp).
#include "scene/batch_run.hpp"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "core/error.hpp"
#include "core/progress_bar.hpp"
#include "core/stopwatch.hpp"
#include "export/atomic_file.hpp"
#include "scene/flight_frames.hpp"
#include "scene/frame_output.hpp"
#include "scene/mesh_frames.hpp"
#include "scene/scene_inputs.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/timing_tables.hpp"

namespace penink {

namespace {

namespace fs = std::filesystem;

// What a run flies: one camera per frame, the frames' source, and (a terrain) the flight records
// with their per-frame scene values.
struct BatchFlight {
    std::vector<Camera> cameras;
    std::vector<FlightRecord> records;  // empty for an orbit
    std::unique_ptr<FrameSource> frames;
};

// Checks that --path / --orbit / --whole-dem fit the scene's input.
void check_flight_options(const BatchRun& o, bool mesh) {
    if (mesh && !o.path.empty())
        throw Error("batch", o.path, "a flight path flies over a terrain; a mesh scene takes --orbit N");
    if (mesh && o.orbit == 0) throw Error("batch", o.input, "a mesh scene needs --orbit N (frames around the model)");
    if (mesh && o.whole_dem) throw Error("batch", o.input, "--whole-dem: a mesh scene has no DEM");
    if (!mesh && o.orbit > 0) throw Error("batch", o.input, "--orbit flies around a mesh; a terrain takes --path CSV");
    if (!mesh && o.path.empty()) throw Error("batch", o.input, "a terrain needs --path CSV (the flight path)");
}

// The output folder, made and checked before anything is drawn.
void prepare_out_dir(const BatchRun& o, const Scene& scene) {
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (!fs::is_directory(o.out_dir)) throw Error("batch", o.out_dir, "cannot create the output directory");
    check_output_targets(batch_frame_paths(o.out_dir, 1, o.formats), PageOptions{}, scene.view.camera.width,
                         scene.view.camera.height);
}

void write_text(const fs::path& p, const std::string& text) { write_file_atomically(p.string(), text); }

}  // namespace

std::vector<std::string> batch_frame_paths(const std::string& out_dir, int frame, const std::vector<std::string>& formats) {
    std::ostringstream name;
    name << "frame_" << std::setw(4) << std::setfill('0') << frame;
    std::vector<std::string> paths;
    for (const std::string& f : formats) paths.push_back((fs::path(out_dir) / (name.str() + "." + f)).string());
    return paths;
}

std::string run_batch_frames(Scene& scene, const BatchRun& o, Clock::time_point start, const Log& log) {
    BatchSummary summary;
    summary.mesh = is_mesh_scene(scene);
    check_flight_options(o, summary.mesh);
    const Style& style = scene.style.resolved;
    summary.scene = o.input, summary.warmup = o.warmup;
    summary.width = scene.view.camera.width, summary.height = scene.view.camera.height;
    std::unique_ptr<GlContext> context;  // outlives the frames' GL objects
    BatchFlight flight;
    if (summary.mesh) {
        context = make_gl_context(o.gl);
        auto mesh = std::make_unique<MeshFrames>(scene, *context, log);
        flight.cameras = mesh->orbit(scene, o.orbit);
        summary.triangles = mesh->triangles();
        flight.frames = std::move(mesh);
        prepare_out_dir(o, scene);
    } else {
        Flight f = plan_flight(scene, o.path, o.whole_dem, log);
        prepare_out_dir(o, scene);
        context = make_gl_context(o.gl);
        summary.cells = f.model.cells();
        summary.dem_cells = std::size_t(f.dem.stored.meta.cols - 1) * (f.dem.stored.meta.rows - 1);
        flight.frames = std::make_unique<TerrainFrames>(*context, scene_drainage(scene, f.dem, log), std::move(f.model),
                                                        summary.width, summary.height, log,
                                                        LineCulling{f.cameras, line_culling_px(scene)});
        flight.cameras = std::move(f.cameras), flight.records = std::move(f.records);
    }
    summary.machine = context->description();
    summary.setup_s = ms_since(start) / 1000.0;
    std::vector<FrameTiming> timings;
    // A shard draws its frames from the whole flight's set-up (window, depth range, line culling
    // for every camera), so each frame is what an unsharded run draws. Warm-up: the first frames
    // this run draws (its shader JIT and caches).
    const int shard = o.shard, shards = o.shards;
    const std::size_t count = flight.cameras.size();
    const std::string stem = shards > 1 ? "timings_" + std::to_string(shard) + "-of-" + std::to_string(shards) : "timings";
    {  // no frame or table replaces an input (a DEM or flight path kept in the output folder)
        std::vector<std::string> outs = {(fs::path(o.out_dir) / (stem + ".csv")).string(),
                                         (fs::path(o.out_dir) / (stem + ".md")).string()};
        for (std::size_t i = 0; i < count; ++i)
            for (std::string& p : batch_frame_paths(o.out_dir, int(i) + 1, o.formats)) outs.push_back(std::move(p));
        std::vector<NamedInput> inputs = scene_inputs(scene);
        if (!o.path.empty()) inputs.push_back({o.path, "the flight path"});
        check_outputs_are_not_inputs(outs, inputs);
    }
    const int drawn = (int(count) - shard) / shards + 1;
    ProgressBar bar(std::cerr, log.progress, "batch", std::max(drawn, 0));
    for (std::size_t i = std::size_t(shard - 1); i < count; i += std::size_t(shards)) {
        const auto t0 = Clock::now();
        FrameTiming t;
        t.frame = int(i) + 1, t.warmup = int(timings.size()) < o.warmup;
        SceneDrawing d = flight.frames->draw(flight.cameras[i],
                                             flight.records.empty() ? scene : frame_scene(scene, flight.records[i]));
        t.times = d.times, t.lines = d.lines, t.trace = d.trace_ms;
        FrameOutput output{batch_frame_paths(o.out_dir, t.frame, o.formats), {}, LayerSplit::kind, ""};
        output.furniture = scene.view.furniture, output.map_scale = scene.view.map_scale;
        const FrameOutputResult e = write_frame(d.drawing, style, scene.style.seed, !summary.mesh, output);
        t.finish = e.finish_ms, t.write = e.write_ms;
        t.total = ms_since(t0);
        timings.push_back(t);
        bar.step(fs::path(batch_frame_paths(o.out_dir, t.frame, o.formats)[0]).stem().string(), t.total);
    }
    bar.finish();
    write_text(fs::path(o.out_dir) / (stem + ".csv"), timings_csv(timings, summary.mesh));
    const std::string md = timings_markdown(timings, summary);
    write_text(fs::path(o.out_dir) / (stem + ".md"), md);
    return md;
}

}  // namespace penink
