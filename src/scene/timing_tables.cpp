#include "scene/timing_tables.hpp"

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace penink {

double passes_total(const FrameTiming& f) {
    const PassTimings& t = f.times;
    return t.tft + t.aft + t.dm + t.sil + t.ridges + f.lay();
}

namespace {

// m += k * f, field by field (every time of a frame).
void add_scaled(FrameTiming& m, const FrameTiming& f, double k) {
    PassTimings& t = m.times;
    t.tft += k * f.times.tft, t.aft += k * f.times.aft, t.dm += k * f.times.dm, t.sil += k * f.times.sil;
    t.ridges += k * f.times.ridges, t.readback += k * f.times.readback, t.pel += k * f.times.pel;
    MeshLineTimings& l = m.lines;
    l.normals += k * f.lines.normals, l.pel_geometry += k * f.lines.pel_geometry, l.pel += k * f.lines.pel;
    l.silhouettes += k * f.lines.silhouettes, l.features += k * f.lines.features;
    l.textures += k * f.lines.textures, l.visibility += k * f.lines.visibility;
    m.trace += k * f.trace, m.finish += k * f.finish, m.write += k * f.write, m.total += k * f.total;
}

// Mean over the frames of 1000 / time(f), frames with time 0 left out.
template <class Time>
double mean_fps(const std::vector<const FrameTiming*>& frames, Time time) {
    double sum = 0;
    int n = 0;
    for (const FrameTiming* f : frames)
        if (const double t = time(*f); t > 0) sum += 1000.0 / t, ++n;
    return n > 0 ? sum / n : 0.0;
}

TimingRow row_of(const std::vector<const FrameTiming*>& frames, const std::string& name) {
    TimingRow r;
    r.frames = name, r.n = int(frames.size());
    for (const FrameTiming* f : frames) add_scaled(r.mean, *f, 1.0 / r.n);
    r.crease_fps = mean_fps(frames, [](const FrameTiming& f) { return f.times.tft + f.times.dm; });
    r.silh_fps = mean_fps(frames, [](const FrameTiming& f) { return f.times.tft + f.times.aft + f.times.sil; });
    r.total_fps = mean_fps(frames, passes_total);
    r.frame_fps = mean_fps(frames, [](const FrameTiming& f) { return f.total; });
    return r;
}

}  // namespace

std::vector<TimingRow> timing_rows(const std::vector<FrameTiming>& frames) {
    std::vector<const FrameTiming*> warm, rest;
    for (const FrameTiming& f : frames) (f.warmup ? warm : rest).push_back(&f);
    std::vector<TimingRow> rows;
    if (!warm.empty()) rows.push_back(row_of(warm, "warm-up"));
    if (!rest.empty()) rows.push_back(row_of(rest, "after warm-up"));
    return rows;
}

std::string timings_csv(const std::vector<FrameTiming>& frames, bool mesh) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    if (mesh)
        s << "frame,warmup,tft,aft,sil,readback,normals,pel_geometry,pel,silhouettes,features,textures,visibility,"
             "lines,sketch,export,total\n";
    else
        s << "frame,warmup,tft,aft,dm,sil,ridges,lay,readback,trace,total\n";
    for (const FrameTiming& f : frames) {
        const PassTimings& t = f.times;
        const MeshLineTimings& l = f.lines;
        s << f.frame << "," << (f.warmup ? 1 : 0) << "," << t.tft << "," << t.aft << ",";
        if (mesh)
            s << t.sil << "," << t.readback << "," << l.normals << "," << l.pel_geometry << "," << l.pel << ","
              << l.silhouettes << "," << l.features << "," << l.textures << "," << l.visibility << "," << f.trace
              << "," << f.finish << "," << f.write << "," << f.total << "\n";
        else
            s << t.dm << "," << t.sil << "," << t.ridges << "," << f.lay() << "," << t.readback << "," << f.trace
              << "," << f.total << "\n";
    }
    return s.str();
}

namespace {

void terrain_tables(std::ostream& s, const std::vector<TimingRow>& rows) {
    s << "## Pass times (creases paper, Table 3): mean ms per frame\n\n"
      << "| frames | n | TFT | AFT | DM | SIL | RIDGES | LAY | TOTAL | read-back | trace | frame |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const TimingRow& r : rows) {
        const FrameTiming& m = r.mean;
        const PassTimings& t = m.times;
        s << "| " << r.frames << " | " << r.n << " | " << t.tft << " | " << t.aft << " | " << t.dm << " | " << t.sil
          << " | " << t.ridges << " | " << m.lay() << " | " << passes_total(m) << " | " << t.readback << " | "
          << m.trace << " | " << m.total << " |\n";
    }
    s << "\n## Frame rates (creases paper, Table 4): mean over frames of 1000 / t ms\n\n"
      << "| frames | n | CREASEfps | SILHfps | TOTALfps | FRAMEfps |\n"
      << "|---|---|---|---|---|---|\n";
    for (const TimingRow& r : rows)
        s << "| " << r.frames << " | " << r.n << " | " << r.crease_fps << " | " << r.silh_fps << " | " << r.total_fps
          << " | " << r.frame_fps << " |\n";
}

void mesh_table(std::ostream& s, const std::vector<TimingRow>& rows, const BatchSummary& b) {
    const std::string model = std::filesystem::path(b.scene).stem().string();
    s << "## Walk-through frame times (walkthrough paper, Table 1): mean ms per frame\n\n"
      << "| model | triangles | frames | n | TFT | SIL | read-back | normals | PEL geometry | PEL | silhouettes | "
         "feature edges | textures | visibility | lines | sketch | export | frame | fps |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const TimingRow& r : rows) {
        const FrameTiming& m = r.mean;
        const MeshLineTimings& l = m.lines;
        s << "| " << model << " | " << b.triangles << " | " << r.frames << " | " << r.n << " | "
          << m.times.tft + m.times.aft << " | " << m.times.sil << " | " << m.times.readback << " | " << l.normals
          << " | " << l.pel_geometry << " | " << l.pel << " | " << l.silhouettes << " | " << l.features << " | "
          << l.textures << " | " << l.visibility << " | " << m.trace << " | " << m.finish << " | " << m.write
          << " | " << m.total << " | " << r.frame_fps << " |\n";
    }
}

}  // namespace

std::string timings_markdown(const std::vector<FrameTiming>& frames, const BatchSummary& b) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1);
    s << "# penink batch timings\n\n"
      << "- scene: " << b.scene << ", " << b.width << "x" << b.height << " pixels\n"
      << "- machine: " << b.machine << "\n";
    if (b.mesh)
        s << "- model: " << b.triangles << " triangles; set-up " << std::setprecision(3) << b.setup_s
          << " s (mesh read, subdivided, GPU upload)\n";
    else
        s << "- modelled: " << b.cells << " of " << b.dem_cells << " DEM cells; set-up " << std::setprecision(3)
          << b.setup_s << " s (DEM, mesh, GPU upload, drainage)\n";
    s << std::setprecision(1) << "- warm-up: the first " << b.warmup
      << " frames this run drew (shader JIT, caches), a row of their own\n";
    if (b.mesh)
        s << "- TFT = the depth pass (toward and away), lines = every object-space line of the frame with its "
             "visibility (normals ... visibility are its parts), sketch = finish (sketch, thinning, plotter "
             "order), export = style and write the frame's files; fps = mean over frames of 1000 / frame ms\n\n";
    else
        s << "- TFT holds the whole TFT+AFT pass when they run combined (AFT 0); LAY = finish, style and export of "
             "the frame's files; TOTAL = TFT+AFT+DM+SIL+RIDGES+LAY; trace = images to polylines (CPU); frame = "
             "wall time of the whole frame\n"
          << "- fps = mean over frames of 1000 / t: CREASEfps t = TFT+DM, SILHfps t = TFT+AFT+SIL, TOTALfps t = "
             "TOTAL, FRAMEfps t = frame\n\n";
    const std::vector<TimingRow> rows = timing_rows(frames);
    if (b.mesh)
        mesh_table(s, rows, b);
    else
        terrain_tables(s, rows);
    return s.str();
}

}  // namespace penink
