// Golden snapshots of the whole `penink render` pipeline (draw_scene -> finish_drawing ->
// style_drawing -> SVG) on volcano at 200x150 with the technical and field-sketch styles, plus
// determinism (same args twice -> same bytes; another --seed -> other bytes with field-sketch)
// and the metadata/page options reaching the files. See tests/cli/golden/README.md for how
// the snapshots are regenerated (PENINK_UPDATE_GOLDEN=1) and what they depend on.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

namespace fs = std::filesystem;

const fs::path examples = PENINK_SOURCE_DIR "/examples";
const fs::path golden_dir = PENINK_SOURCE_DIR "/tests/cli/golden";

// A fresh directory holding a copy of examples/volcano.asc (+ .prj): penink runs there with a
// relative input path, so the metadata names no directory of this machine and the drainage
// cache (volcano.asc.dv) is written there, not into the source tree.
fs::path volcano_dir(const std::string& name) {
    const fs::path dir = fresh_dir(name);
    for (const char* f : {"volcano.asc", "volcano.prj"}) fs::copy_file(examples / f, dir / f);
    return dir;
}

// Renders volcano.asc in `dir` at 200x150 to `out` with the given extra arguments.
std::string render(const fs::path& dir, const std::string& out, const std::string& args) {
    const RunResult r = run_penink("render volcano.asc --width 200 --height 150 -o " + out + " " + args, dir);
    EXPECT_EQ(r.code, 0) << r.output;
    return read_text(dir / out);
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

std::string clip(const std::string& s) { return s.size() > 160 ? s.substr(0, 160) + "..." : s; }

// Empty when equal; otherwise sizes, line and path counts, and the first differing line.
std::string diff_summary(const std::string& want, const std::string& got) {
    if (want == got) return "";
    const auto a = lines_of(want), b = lines_of(got);
    size_t differing = 0, first = std::min(a.size(), b.size());
    for (size_t i = 0; i < std::max(a.size(), b.size()); ++i)
        if (i >= a.size() || i >= b.size() || a[i] != b[i]) {
            first = std::min(first, i);
            ++differing;
        }
    const auto paths = [](const std::vector<std::string>& v) {
        return std::count_if(v.begin(), v.end(), [](const std::string& l) { return l.rfind("<path d=", 0) == 0; });
    };
    std::ostringstream s;
    s << "golden " << want.size() << " bytes, " << a.size() << " lines, " << paths(a) << " paths; got "
      << got.size() << " bytes, " << b.size() << " lines, " << paths(b) << " paths; " << differing
      << " lines differ, first at line " << first + 1 << ":\n  golden: " << (first < a.size() ? clip(a[first]) : "<eof>")
      << "\n  got:    " << (first < b.size() ? clip(b[first]) : "<eof>");
    return s.str();
}

void expect_golden(const std::string& got, const std::string& name) {
    const fs::path file = golden_dir / name;
    if (std::getenv("PENINK_UPDATE_GOLDEN")) {
        std::ofstream(file, std::ios::binary) << got;
        std::printf("updated %s\n", file.c_str());
    }
    ASSERT_TRUE(fs::exists(file)) << file << " missing (run with PENINK_UPDATE_GOLDEN=1)";
    const std::string summary = diff_summary(read_text(file), got);
    EXPECT_EQ(summary, "") << "output differs from " << file << " (see tests/cli/golden/README.md)";
}

}  // namespace

TEST(GoldenRender, VolcanoTechnical) {
    const auto dir = volcano_dir("golden_tech");
    expect_golden(render(dir, "a.svg", "--style technical"), "volcano_technical.svg");
}

TEST(GoldenRender, VolcanoFieldSketchAndSeeds) {
    const auto dir = volcano_dir("golden_sketch");
    const std::string a = render(dir, "a.svg", "--style field-sketch --seed 3");
    expect_golden(a, "volcano_field_sketch.svg");
    EXPECT_EQ(render(dir, "b.svg", "--style field-sketch --seed 3"), a);  // run twice: same bytes
    const std::string c = render(dir, "c.svg", "--style field-sketch --seed 4");
    EXPECT_NE(c, a);
    // Not only the metadata: the geometry of the strokes changes with the seed.
    const auto la = lines_of(a), lc = lines_of(c);
    size_t same_paths = 0, paths = 0;
    for (size_t i = 0; i < std::min(la.size(), lc.size()); ++i)
        if (la[i].rfind("<path d=", 0) == 0) ++paths, same_paths += la[i] == lc[i];
    EXPECT_GT(paths, 20u);
    EXPECT_LT(same_paths, paths / 10);
}

TEST(GoldenRender, MetadataAndPageReachEveryFormat) {
    const auto dir = volcano_dir("golden_meta");
    const RunResult r = run_penink("render volcano.asc --width 200 --height 150 --page A5 --margin 10 "
                                   "-o m.svg -o m.ps -o m.pdf", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "m.svg"), ps = read_text(dir / "m.ps"), pdf = read_text(dir / "m.pdf");
    // A5 landscape 210 x 148 mm; 200x150 px scaled into 190 x 128 mm -> 0.8533 mm/px.
    EXPECT_NE(svg.find("width=\"210mm\" height=\"148mm\""), std::string::npos) << svg.substr(0, 600);
    EXPECT_NE(svg.find("<penink:param name=\"source\">volcano.asc</penink:param>"), std::string::npos);
    EXPECT_NE(svg.find("<penink:param name=\"light\">azimuth 315, altitude 45</penink:param>"), std::string::npos);
    EXPECT_NE(svg.find("<penink:param name=\"camera\">eye "), std::string::npos);
    EXPECT_NE(svg.find("<penink:param name=\"parameters\">vertical_exaggeration 1"), std::string::npos);
    EXPECT_NE(ps.find("\n% penink source: volcano.asc\n"), std::string::npos);
    EXPECT_NE(ps.find("\n% penink light: azimuth 315, altitude 45\n"), std::string::npos);
    EXPECT_NE(ps.find("%%BoundingBox: 0 0 596 420\n"), std::string::npos);
    EXPECT_NE(pdf.find("/penink_source (volcano.asc)"), std::string::npos);
    EXPECT_NE(pdf.find("/penink_light (azimuth 315, altitude 45)"), std::string::npos);
}
