// Frame times of `penink preview`, without a browser: the drawing thread's own calls
// (preview/preview_session.hpp's PreviewSession, as preview_server.cpp makes and calls it) on each
// input given. Per input: the start (the session made: the scene's own view drawn once) and the
// page's first full frame; full frames after a camera change (the view orbited 10 degrees each,
// as after letting go of the mouse); drag frames (0.4 of the size, the page's DRAG_SCALE, orbited
// 2 degrees each). Prints the median and slowest wall time of each kind, its process CPU time
// (every thread, llvmpipe's included: what the frame costs on an idle machine of as many cores)
// and the ratio of the wall median to the target (full frames: the input's target; drag frames:
// 0.5 s), with the load average, since on a shared machine the wall time follows the load.
// Usage: preview_frames_bench [-v] [--runs N] [--cache-dir DIR] INPUT TARGET_S [INPUT TARGET_S ...]
// (bench/preview_speed.sh runs it on examples/volcano.asc and jacksboro refined 5x).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/stopwatch.hpp"
#include "preview/preview_session.hpp"
#include "scene/scene_overrides.hpp"

using namespace penink;

namespace {

double cpu_ms() {  // this process, every thread
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return (u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e3;
}

std::string load_average() {
    std::ifstream f("/proc/loadavg");
    std::string one, five;
    f >> one >> five;
    return one + " " + five;
}

struct Timed {
    double wall = 0.0, cpu = 0.0;
};

template <class F>
Timed timed(F&& f) {
    const double c0 = cpu_ms();
    const auto t0 = Clock::now();
    f();
    return {ms_since(t0), cpu_ms() - c0};
}

void report(const char* what, std::vector<Timed> runs, double target_s) {
    std::sort(runs.begin(), runs.end(), [](const Timed& a, const Timed& b) { return a.wall < b.wall; });
    const Timed& median = runs[runs.size() / 2];
    std::printf("  %-34s wall median %7.0f ms, max %7.0f ms; CPU %7.0f ms; / target %.1f s = %.2f\n", what, median.wall,
                runs.back().wall, median.cpu, target_s, median.wall / (1e3 * target_s));
}

void bench_input(const std::string& input, double full_target_s, int runs, const std::string& cache_dir, bool verbose) {
    SceneOverrides o;
    o.input = input;
    o.cache_dir = cache_dir;
    const Scene scene = load_scene_with_overrides(o);
    const Log log{verbose, ProgressMode::off};
    const std::string save = (std::filesystem::temp_directory_path() / "preview_frames_bench-view.toml").string();
    std::printf("%s (load average %s)\n", input.c_str(), load_average().c_str());

    std::unique_ptr<PreviewSession> session;
    PreviewFrame frame;
    const Timed start = timed([&] { session = std::make_unique<PreviewSession>(scene, save, GlBackend::osmesa, log); });
    PreviewView view = session->initial_view();
    const Timed first = timed([&] { frame = session->draw(view, 1.0); });
    std::printf("  %-34s wall %7.0f ms; CPU %7.0f ms\n", "start (the session, its own view)", start.wall, start.cpu);
    std::printf("  %-34s wall %7.0f ms; CPU %7.0f ms; %dx%d, %zu bytes of SVG\n", "first full frame", first.wall,
                first.cpu, frame.width, frame.height, frame.svg.size());

    std::vector<Timed> full, drag;
    for (int i = 0; i < runs; ++i) {
        view.azimuth = std::fmod(view.azimuth + 10.0, 360.0);
        full.push_back(timed([&] { session->draw(view, 1.0); }));
    }
    for (int i = 0; i < runs; ++i) {
        view.azimuth = std::fmod(view.azimuth + 2.0, 360.0);
        drag.push_back(timed([&] { frame = session->draw(view, 0.4); }));
    }
    report("full frame after a camera change", full, full_target_s);
    char what[64];
    std::snprintf(what, sizeof what, "drag frame (%dx%d)", frame.width, frame.height);
    report(what, drag, 0.5);
    std::printf("  (load average after: %s)\n", load_average().c_str());
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    int runs = 5;
    bool verbose = false;
    std::string cache_dir;
    std::vector<std::pair<std::string, double>> inputs;
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "-v") verbose = true;
        else if (args[i] == "--runs" && i + 1 < args.size()) runs = std::max(1, std::atoi(args[++i].c_str()));
        else if (args[i] == "--cache-dir" && i + 1 < args.size()) cache_dir = args[++i];
        else if (i + 1 < args.size()) inputs.emplace_back(args[i], std::atof(args[i + 1].c_str())), ++i;
        else inputs.clear(), i = args.size();
    }
    if (inputs.empty() || std::any_of(inputs.begin(), inputs.end(), [](const auto& p) { return !(p.second > 0.0); })) {
        std::fprintf(stderr, "usage: preview_frames_bench [-v] [--runs N] [--cache-dir DIR] INPUT TARGET_S [INPUT TARGET_S ...]\n");
        return 2;
    }
    try {
        for (const auto& [input, target] : inputs) bench_input(input, target, runs, cache_dir, verbose);
    } catch (const Error& e) {
        std::fprintf(stderr, "preview_frames_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
