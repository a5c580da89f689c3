// What the hachures cost: the same `penink render` of a terrain (scene, style, GL context, DEM,
// view window, surface, the frame, finishing, styling, SVG export in memory: render_command's
// steps) with and without the hachures layer, each in a process of its own (fork) so that its
// peak resident memory (getrusage's ru_maxrss of the child) is its own. Runs alternate, off then
// on, RUNS times each, after one untimed render (caches on disk); the minimum wall time of each and the ratios (on / off) of time, of the
// frame's share of it, and of peak memory are printed. The same run also draws the frame a
// second time (warm: caches and shaders ready) and reports its ratio.
// Usage: hachure_cost_bench INPUT [--map] [--width W] [--height H] [--runs N]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "render/gl_context.hpp"
#include "scene/frame_output.hpp"
#include "scene/scene_style.hpp"
#include "scene/terrain_frames.hpp"

using namespace penink;
using Clock = std::chrono::steady_clock;

namespace {

struct Times {
    double total_ms = 0, frame_ms = 0, warm_ms = 0, hachure_ms = 0, warm_hachure_ms = 0;
    double hachures = 0;  // strokes in the hachures layer
};

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

Times render_once(const std::string& input, bool map, int width, int height, bool hachures) {
    const auto start = Clock::now();
    Scene scene = load_scene(input);
    if (map) {
        scene.view.camera.projection = Projection::orthographic;
        scene.view.camera.azimuth = 0.0, scene.view.camera.altitude = -90.0;
        scene.view.camera.position.reset(), scene.view.camera.elevation.reset();
    }
    if (width > 0) scene.view.camera.width = width;
    if (height > 0) scene.view.camera.height = height;
    scene.lines.hachures.enabled = hachures;
    validate_scene(scene);
    const Style& style = scene.style.resolved;
    const auto context = make_gl_context();
    const Log quiet;
    SceneView view = open_terrain_view(scene, *context, quiet);
    const auto t_frame = Clock::now();
    SceneDrawing d = view.frames->draw(view.camera, scene);
    Times t;
    t.frame_ms = ms_since(t_frame);
    t.hachure_ms = d.hachure_ms;
    t.hachures = double(d.drawing.layer(LayerKind::hachures).strokes.size());
    FrameOutput out;
    out.document_format = "svg";
    out.line_measures = false;  // as `penink render` without -v, which alone prints them
    const FrameOutputResult written = write_frame(d.drawing, style, scene.style.seed, true, out);
    if (written.document.empty()) std::exit(3);
    t.total_ms = ms_since(start);
    const auto t_warm = Clock::now();
    const SceneDrawing again = view.frames->draw(view.camera, scene);
    t.warm_ms = ms_since(t_warm);
    t.warm_hachure_ms = again.hachure_ms;
    return t;
}

// The render in a child process: its times through a pipe, its peak memory (KiB) from wait4.
bool run_child(const std::string& input, bool map, int width, int height, bool hachures, Times& t, long& max_rss_kib) {
    int fd[2];
    if (pipe(fd) != 0) return false;
    const pid_t pid = fork();
    if (pid < 0) return false;
    if (pid == 0) {
        close(fd[0]);
        int rc = 0;
        try {
            const Times r = render_once(input, map, width, height, hachures);
            if (write(fd[1], &r, sizeof r) != ssize_t(sizeof r)) rc = 4;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "hachure_cost_bench: %s\n", e.what());
            rc = 2;
        }
        close(fd[1]);
        _exit(rc);
    }
    close(fd[1]);
    const ssize_t got = read(fd[0], &t, sizeof t);
    close(fd[0]);
    int status = 0;
    rusage usage{};
    if (wait4(pid, &status, 0, &usage) != pid) return false;
    max_rss_kib = usage.ru_maxrss;
    return got == ssize_t(sizeof t) && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: hachure_cost_bench INPUT [--map] [--width W] [--height H] [--runs N]\n");
        return 2;
    }
    const std::string input = argv[1];
    bool map = false;
    int width = 0, height = 0, runs = 3;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&] { return i + 1 < argc ? std::atoi(argv[++i]) : 0; };
        if (a == "--map") map = true;
        else if (a == "--width") width = next();
        else if (a == "--height") height = next();
        else if (a == "--runs") runs = std::clamp(next(), 1, 100);
        else {
            std::fprintf(stderr, "hachure_cost_bench: unknown option %s\n", a.c_str());
            return 2;
        }
    }
    {  // untimed: a first render builds what later ones read from disk (the drainage cache)
        Times t;
        long r = 0;
        if (!run_child(input, map, width, height, false, t, r)) {
            std::fprintf(stderr, "hachure_cost_bench: the first render failed\n");
            return 2;
        }
    }
    Times best[2];
    long rss[2] = {0, 0};
    for (Times& b : best) b.total_ms = b.frame_ms = b.warm_ms = 1e300;
    for (int k = 0; k < runs; ++k)
        for (int on = 0; on < 2; ++on) {
            Times t;
            long r = 0;
            if (!run_child(input, map, width, height, on == 1, t, r)) {
                std::fprintf(stderr, "hachure_cost_bench: the render %s hachures failed\n", on ? "with" : "without");
                return 2;
            }
            Times& b = best[on];
            b.total_ms = std::min(b.total_ms, t.total_ms);
            b.frame_ms = std::min(b.frame_ms, t.frame_ms);
            if (t.warm_ms < b.warm_ms) b.warm_ms = t.warm_ms, b.warm_hachure_ms = t.warm_hachure_ms;
            b.hachure_ms = on ? (k == 0 ? t.hachure_ms : std::min(b.hachure_ms, t.hachure_ms)) : 0.0;
            b.hachures = t.hachures;
            rss[on] = std::max(rss[on], r);
        }
    std::printf("%s%s: best of %d renders each, %.0f hachures\n", input.c_str(), map ? " (map)" : "", runs, best[1].hachures);
    std::printf("%-10s %12s %12s %12s %14s\n", "", "render ms", "frame ms", "warm frame", "peak MiB");
    for (int on = 0; on < 2; ++on)
        std::printf("%-10s %12.0f %12.0f %12.0f %14.1f\n", on ? "hachures" : "without", best[on].total_ms, best[on].frame_ms,
                    best[on].warm_ms, rss[on] / 1024.0);
    std::printf("hachures ms: %.0f (first frame), %.0f (warm frame)\n", best[1].hachure_ms, best[1].warm_hachure_ms);
    std::printf("ratio with / without: render %.2f  frame %.2f  warm frame %.2f  peak memory %.2f\n",
                best[1].total_ms / best[0].total_ms, best[1].frame_ms / best[0].frame_ms, best[1].warm_ms / best[0].warm_ms,
                double(rss[1]) / double(std::max(rss[0], 1L)));
    return 0;
}
