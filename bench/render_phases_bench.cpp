// Where the time of one `penink render` of a terrain scene goes, phase by phase (wall ms, one
// process, same steps as cli/render_command): scene, GL context, DEM read,
// camera + view window, surface mesh, renderer (shader programs), drainage cache load, drainage
// line sets (GPU upload), the frame (passes + tracing), finishing, styling, SVG export; then the
// same frame again (warm). Usage: render_phases_bench SCENE [WIDTH HEIGHT]. Process start-up
// (shared libraries) is outside: measure it with bench/speed_target.sh.
#include <chrono>
#include <cstdio>
#include <string>

#include "scene/frame_output.hpp"
#include "scene/drainage_lines.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"
#include "drainage/drainage_build.hpp"
#include "export/style.hpp"
#include "input/dem_reader.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;
using Clock = std::chrono::steady_clock;

namespace {

struct Phases {
    Clock::time_point last = Clock::now(), start = last;
    void mark(const char* name) {
        const auto now = Clock::now();
        std::printf("%-34s %8.1f ms\n", name, std::chrono::duration<double, std::milli>(now - last).count());
        last = now;
    }
    void total() const {
        std::printf("%-34s %8.1f ms\n", "total (in process)",
                    std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: render_phases_bench SCENE [WIDTH HEIGHT]\n");
        return 2;
    }
    Phases p;
    Scene scene = load_scene(argv[1]);
    if (argc >= 4) scene.view.camera.width = std::stoi(argv[2]), scene.view.camera.height = std::stoi(argv[3]);
    const Style style = resolve_style(scene.style.name);
    p.mark("scene + style");
    const auto context = make_gl_context(GlBackend::osmesa);
    p.mark("GL context");
    DemOptions dem_options;
    dem_options.vertical_exaggeration = scene.terrain.vertical_exaggeration;
    const Terrain dem = read_dem(scene.source.dem, dem_options);
    p.mark("DEM read (GDAL)");
    const Log quiet;
    Camera camera = scene_camera(scene, dem);
    const Terrain view = terrain_for_view(dem, camera, scene, quiet);
    p.mark("camera + view window");
    const SurfaceMesh mesh = mesh_from_terrain(view);
    p.mark("surface mesh");
    TerrainRenderer renderer(context->gl(), mesh, camera.width, camera.height);
    p.mark("renderer (programs)");
    const DrainageDb db = load_or_build_drainage(scene.source.dem, dem, DrainageOptions{}, [](const std::string&) {});
    p.mark("drainage cache load");
    DrainageLines lines(context->gl(), db, view);
    p.mark("drainage line sets");
    p.last = Clock::now();
    // The frame itself, as TerrainFrames::draw (a second TerrainFrames would redo the set-up).
    TerrainFrames frames(*context, scene_drainage(scene, dem, quiet), view, camera.width, camera.height, quiet);
    p.mark("(TerrainFrames set-up, all of it)");
    SceneDrawing d = frames.draw(camera, scene);
    p.mark("frame: passes + tracing");
    const FrameOutputResult lay_times =
        write_frame(d.drawing, style, scene.style.seed, true, FrameOutput{{"/tmp/render_phases_bench.svg"}, {}, LayerSplit::kind, ""});
    const double lay = lay_times.finish_ms + lay_times.write_ms;
    std::printf("%-34s %8.1f ms\n", "finish + style + SVG", lay);
    p.last = Clock::now();
    SceneDrawing again = frames.draw(camera, scene);
    p.mark("same frame again (warm)");
    std::printf("GPU ms: TFT %.1f SIL %.1f DM %.1f RIDGES %.1f read-back %.1f; trace %.1f\n", d.times.tft,
                d.times.sil, d.times.dm, d.times.ridges, d.times.readback, d.trace_ms);
    p.total();
    return 0;
}
