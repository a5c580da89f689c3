// Screen-size culling of creases and ridges (prepare_drainage_lines with line_culling_px) leaves
// the drawing as it is: every stroke the spacing thinning keeps is three spacings long at least,
// and the culling drops only pieces whose image length is bounded below that. Checked on
// jacksboro (whole DEM in view, and a narrow view of its far side where most lines are small), at
// exaggeration 2, with the technical style (no sketch) and with sketchy lines, by drawing each
// frame with the culling and without it (the same decimation) and comparing the layers' strokes.
#include <gtest/gtest.h>

#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"
#include "scene/drainage_lines.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"
#include "support/gl_test_context.hpp"

using namespace penink;

namespace {

void expect_same_strokes(const std::vector<Stroke>& a, const std::vector<Stroke>& b, const std::string& what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].points, b[i].points) << what << " stroke " << i;
        ASSERT_EQ(a[i].strength, b[i].strength) << what << " stroke " << i;
    }
}

}  // namespace

TEST(LineCulling, DrawingIsTheSameWithAndWithoutIt) {
    const std::string path = PENINK_SOURCE_DIR "/examples/jacksboro.tif";
    const DrainageDb db = drainage_lines_only(build_drainage_db(read_dem(path), DrainageOptions{}));
    DemOptions o;
    o.vertical_exaggeration = 2.0;
    const Terrain dem = read_dem(path, o);
    Scene scene;
    scene.terrain.vertical_exaggeration = 2.0;
    scene.view.camera.width = 500, scene.view.camera.height = 375;
    Camera whole = scene_camera(scene, dem);
    Camera narrow = whole;
    narrow.fov /= 4.0;  // the far side, magnified
    narrow.azimuth += 5.0;
    std::size_t dropped = 0;
    for (const float sketch : {0.0f, 1.5f}) {
        Scene s = scene;
        s.style.resolved.layer(LayerKind::creases).sketch = s.style.resolved.layer(LayerKind::ridges).sketch = sketch;
        const float min_px = line_culling_px(s);
        EXPECT_GT(min_px, 2.0f);
        for (const Camera& cam : {whole, narrow}) {
            const std::string what = "sketch " + std::to_string(sketch) + " fov " + std::to_string(cam.fov);
            SceneDrawing d[2];
            for (int culled = 0; culled < 2; ++culled) {
                DrainageLineSource source;
                source.db = db;
                TerrainFrames frames(test::test_context(), std::move(source), dem, cam.width, cam.height, Log{},
                                     LineCulling{{cam}, culled ? min_px : 0.0f, 0.5f});
                d[culled] = frames.draw(cam, s);
            }
            const std::size_t all = prepare_drainage_lines(db, dem, LineCulling{{cam}, 0.0f, 0.5f}).creases.runs.size();
            const std::size_t kept = prepare_drainage_lines(db, dem, LineCulling{{cam}, min_px, 0.5f}).creases.runs.size();
            dropped += all - kept;
            EXPECT_GT(d[0].drawing.layer(LayerKind::creases).strokes.size(), 10u) << what;
            expect_same_strokes(d[0].drawing.layer(LayerKind::creases).strokes,
                                d[1].drawing.layer(LayerKind::creases).strokes, what + " creases");
            expect_same_strokes(d[0].drawing.layer(LayerKind::ridges).strokes,
                                d[1].drawing.layer(LayerKind::ridges).strokes, what + " ridges");
        }
    }
    EXPECT_GT(dropped, 1000u);  // the culling does drop pieces here
}
