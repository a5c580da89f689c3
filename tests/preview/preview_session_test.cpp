// A preview session keeps its terrain, drainage lines and GPU passes between frames
// (scene/terrain_keep.hpp): a frame drawn after others of other views, sizes, exaggerations and
// sea levels is, byte for byte, the SVG a fresh `penink render` of the saved view makes; its
// caches go to the --cache-dir given, or to the scene's [cache] dir, never beside the DEM.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "preview/preview_session.hpp"
#include "scene/frame_output.hpp"
#include "scene/map_scale.hpp"
#include "scene/scene_overrides.hpp"
#include "support/gl_test_context.hpp"
#include "support/temp_dir.hpp"

using namespace penink;
namespace fs = std::filesystem;

namespace {

// examples/volcano.asc (61 x 87 nodes, 94..196 m) copied into `folder`: its caches, if written
// beside it, would show there.
std::string copy_volcano(const fs::path& folder) {
    fs::create_directories(folder);
    for (const char* f : {"volcano.asc", "volcano.prj"})
        fs::copy_file(fs::path(PENINK_SOURCE_DIR) / "examples" / f, folder / f);
    return (folder / "volcano.asc").string();
}

std::string read_text(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// The files in `folder` whose names end with `ext`.
int count_with_extension(const fs::path& folder, const std::string& ext) {
    int n = 0;
    if (!fs::is_directory(folder)) return 0;
    for (const auto& e : fs::directory_iterator(folder)) n += e.path().extension() == ext;
    return n;
}

// `penink render` of a saved view: the scene file loaded, checked and drawn to an SVG in memory,
// in a process of its own making (nothing kept).
std::string render_saved(const std::string& path) {
    Scene s = load_scene(path);
    validate_scene(s);
    apply_map_scale(s, PageOptions{});
    FrameOutput out;
    out.document_format = "svg";
    out.line_measures = false;
    return render_scene_frame(s, test::test_context(), out, Log{}).written.document;
}

}  // namespace

TEST(PreviewSession, KeptFramesDrawWhatARenderOfTheSavedViewDraws) {
    test::TempDir dir;
    SceneOverrides o;
    o.input = copy_volcano(dir.path / "dem");
    o.cache_dir = dir.file("cache");
    o.width = 360, o.height = 270;
    PreviewFrame kept, dry;
    {  // the session and its GL context gone before the renders make theirs current
        PreviewSession session(load_scene_with_overrides(o), dir.file("view.toml"), GlBackend::osmesa, Log{});
        PreviewView v = session.initial_view();
        session.draw(v, 1.0);
        v.azimuth += 25.0, v.altitude -= 5.0, v.sea_level = 120.0;  // a drag frame: another size, a sea
        session.draw(v, 0.4);
        v.azimuth += 10.0, v.light_azimuth = 270.0, v.vertical_exaggeration = 2.0;  // the sea pyramid kept
        kept = session.draw(v, 1.0);
        fs::create_directories(dir.path / "kept"), fs::create_directories(dir.path / "dry");
        fs::copy_file(session.save(v), dir.file("kept/view.toml"));  // the same name: the SVG's title
        // then without the sea, at the first exaggeration: the dry pyramid again
        v.sea_level.reset(), v.vertical_exaggeration = session.initial_view().vertical_exaggeration;
        v.azimuth -= 40.0;
        dry = session.draw(v, 1.0);
        fs::copy_file(session.save(v), dir.file("dry/view.toml"));
    }
    ASSERT_EQ(kept.width, 360);
    const std::string fresh = render_saved(dir.file("kept/view.toml"));
    ASSERT_FALSE(fresh.empty());
    EXPECT_TRUE(kept.svg == fresh) << "kept frame " << kept.svg.size() << " bytes, fresh render " << fresh.size();
    EXPECT_TRUE(dry.svg == render_saved(dir.file("dry/view.toml")));

    // the caches went to --cache-dir, not beside the DEM, and the saved view names it
    EXPECT_EQ(count_with_extension(dir.path / "cache", ".lod"), 1);
    EXPECT_EQ(count_with_extension(dir.path / "cache", ".dv"), 1);
    EXPECT_EQ(count_with_extension(dir.path / "dem", ".lod") + count_with_extension(dir.path / "dem", ".dv"), 0);
    EXPECT_NE(read_text(dir.file("dry/view.toml")).find("dir = \"" + dir.file("cache") + "\""), std::string::npos)
        << read_text(dir.file("dry/view.toml"));
}

TEST(PreviewSession, TheScenesCacheDirHoldsTheCaches) {
    test::TempDir dir;
    copy_volcano(dir.path / "dem");
    std::ofstream(dir.file("scene.toml")) << "[terrain]\ndem = \"dem/volcano.asc\"\n"
                                          << "[camera]\nwidth = 200\nheight = 150\n"
                                          << "[cache]\ndir = \"kept\"\n";  // relative to the scene file
    SceneOverrides o;
    o.input = dir.file("scene.toml");
    PreviewSession session(load_scene_with_overrides(o), dir.file("view.toml"), GlBackend::osmesa, Log{});
    PreviewView v = session.initial_view();
    v.azimuth += 30.0;
    session.draw(v, 1.0);
    EXPECT_EQ(count_with_extension(dir.path / "kept", ".lod"), 1);
    EXPECT_EQ(count_with_extension(dir.path / "kept", ".dv"), 1);
    EXPECT_EQ(count_with_extension(dir.path / "dem", ".lod") + count_with_extension(dir.path / "dem", ".dv"), 0);
}
