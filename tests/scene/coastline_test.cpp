// Sea level in terrain frames: the coastline layer on a cone island lies on the closed-form shore
// circle projected with the camera and is hidden where the island occludes it; the water hides
// a seamount (no silhouette over it) and draws no coastline when all of it is under water; on a
// map whose frame cuts the shore the coastline runs to the frame;
// creases and ridges are cut at the sea (no drawable vertex at or below it); and [terrain]
// sea_level is read (a number; strict keys) and validated.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "drainage/drainage_build.hpp"
#include "scene/drainage_lines.hpp"
#include "scene/terrain_frames.hpp"
#include "scene/terrain_view.hpp"
#include "support/gl_test_context.hpp"
#include "support/synthetic_terrain.hpp"
#include "support/temp_dir.hpp"

using namespace penink;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A terrain in memory, all of it modelled, drawn with water at `sea` (metres; exaggeration 1).
FrameTerrain with_sea(Terrain t, double sea) {
    FrameTerrain f = frame_terrain(std::move(t));
    f.nodes.sea_level = sea;
    return f;
}

Scene no_drainage() {
    Scene s;
    s.lines.creases.enabled = s.lines.ridges.enabled = false;
    return s;
}

// Looking north at `altitude` degrees down at the origin from `distance` metres (plan), 800 x 600.
Camera looking_north(double distance, double altitude, const Terrain& t) {
    Camera c;
    c.eye = {0.0, -distance, distance * std::tan(-altitude * kPi / 180.0)};
    c.azimuth = 0.0, c.altitude = altitude, c.fov = 40.0;
    c.width = 800, c.height = 600;
    glm::dvec3 lo, hi;
    terrain_bounds(t, lo, hi);
    fit_depth_range(c, lo, hi);
    return c;
}

double distance_to_segment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

// Distance in pixels from p to the nearest stroke of a layer.
double distance_to_strokes(glm::dvec2 p, const std::vector<Stroke>& strokes) {
    double best = 1e300;
    for (const Stroke& s : strokes)
        for (std::size_t i = 0; i + 1 < s.points.size(); ++i)
            best = std::min(best, distance_to_segment(p, glm::dvec2(s.points[i]), glm::dvec2(s.points[i + 1])));
    return best;
}

glm::dvec2 pixel_of(const Camera& cam, const glm::dvec3& p) {
    glm::dvec2 px;
    double depth;
    EXPECT_TRUE(project_to_pixel(cam, p, px, depth));
    return px;
}

}  // namespace

// A cone island z = 100 - r (45 degree sides, r metres from the centre), 5 m nodes, sea at 0: the
// shore is the circle r = 100, z = 0. Seen from the south 30 degrees down, every coastline point
// lies on that circle projected with the camera, to within the linear interpolation along mesh
// edges (an edge of length h = 5 sqrt(2) bends at most h^2 / (8 r) = 0.06 m from the circle; at
// the nearest shore point's distance that is tol_px below) plus float rounding of the projection
// (1e-3 px). The near shore is drawn; the far shore (behind the cone's top, which rises 100 m
// over the sight line from the eye to it) is hidden.
TEST(Coastline, ConeIslandShoreOnTheProjectedCircle) {
    const Terrain t = terrain_from_function(161, 161, 5.0, [](double x, double y) { return 100.0 - std::hypot(x, y); });
    const Camera cam = looking_north(600.0, -30.0, t);
    TerrainFrames frames(test::test_context(), std::nullopt, with_sea(t, 0.0), cam.width, cam.height, Log{});
    const SceneDrawing d = frames.draw(cam, no_drainage());
    const std::vector<Stroke>& coast = d.drawing.layer(LayerKind::coastline).strokes;
    ASSERT_FALSE(coast.empty());
    std::vector<glm::dvec2> circle;  // 20000 chords of 0.03 m: far finer than a pixel
    for (int i = 0; i <= 20000; ++i) {
        const double a = 2.0 * kPi * i / 20000.0;
        circle.push_back(pixel_of(cam, {100.0 * std::cos(a), 100.0 * std::sin(a), 0.0}));
    }
    const double focal = cam.height / (2.0 * std::tan(cam.fov * kPi / 360.0));
    const double nearest = glm::length(glm::dvec3(0.0, -100.0, 0.0) - cam.eye);
    const double tol_px = 50.0 / (8.0 * 100.0) * focal / nearest + 1e-3;
    std::size_t points = 0;
    double worst = 0.0;
    for (const Stroke& s : coast) {
        EXPECT_EQ(s.kind, "coastline");
        for (const glm::vec2& p : s.points) {
            double best = 1e300;
            for (std::size_t i = 0; i + 1 < circle.size(); ++i)
                best = std::min(best, distance_to_segment(glm::dvec2(p), circle[i], circle[i + 1]));
            EXPECT_LE(best, tol_px) << p.x << " " << p.y;
            worst = std::max(worst, best);
            ++points;
        }
    }
    std::printf("%zu coastline points in %zu strokes, farthest %.4f px from the circle (tolerance %.4f px)\n", points,
                coast.size(), worst, tol_px);
    EXPECT_GT(points, 50u);
    EXPECT_LT(distance_to_strokes(pixel_of(cam, {0.0, -100.0, 0.0}), coast), 0.5);  // the near shore
    EXPECT_LT(distance_to_strokes(pixel_of(cam, {-100.0, 0.0, 0.0}), coast), 0.5);  // its sides
    EXPECT_LT(distance_to_strokes(pixel_of(cam, {100.0, 0.0, 0.0}), coast), 0.5);
    EXPECT_GT(distance_to_strokes(pixel_of(cam, {0.0, 100.0, 0.0}), coast), 20.0);  // behind the cone
}

// A map whose frame cuts the shore: the cone island in plan view (orthographic, north up) 236 m
// across, 177 m high, centred on the cone (its sides between rows of nodes). The shore circle
// r = 100 leaves the frame through its top and bottom sides at x = +-sqrt(100^2 - 88.5^2) =
// +-46.6 m, y = +-88.5 m; each coastline stroke ends on the image border there, not one mesh edge
// short: along the border within the chord error (0.0625 m off the circle, as above) over the sine
// of the angle at which the circle crosses the border (x / 100), at 800 / 236 pixels a metre.
TEST(Coastline, ShoreRunsToTheFrameOfAMap) {
    const Terrain t = terrain_from_function(161, 161, 5.0, [](double x, double y) { return 100.0 - std::hypot(x, y); });
    Camera cam;
    cam.projection = Projection::orthographic;
    cam.azimuth = 0.0, cam.altitude = -90.0;
    cam.width = 800, cam.height = 600;
    cam.view_width = 236.0;
    glm::dvec3 lo, hi;
    terrain_bounds(t, lo, hi);
    cam.eye = {0.0, 0.0, 0.0};
    place_orthographic_eye(cam, lo, hi);
    fit_depth_range(cam, lo, hi);
    TerrainFrames frames(test::test_context(), std::nullopt, with_sea(t, 0.0), cam.width, cam.height, Log{});
    const SceneDrawing d = frames.draw(cam, no_drainage());
    const std::vector<Stroke>& coast = d.drawing.layer(LayerKind::coastline).strokes;
    ASSERT_EQ(coast.size(), 2u);  // the west and the east arcs
    const double y = 88.5, x = std::sqrt(100.0 * 100.0 - y * y);
    const double tol_px = 50.0 / (8.0 * 100.0) / (x / 100.0) * 800.0 / 236.0;
    std::vector<glm::dvec2> exits;
    for (double sx : {-x, x})
        for (double sy : {-y, y}) exits.push_back(pixel_of(cam, {sx, sy, 0.0}));
    for (const Stroke& s : coast)
        for (const glm::vec2& end : {s.points.front(), s.points.back()}) {
            EXPECT_TRUE(std::abs(end.y) < 1e-3 || std::abs(end.y - 600.0f) < 1e-3) << end.x << " " << end.y;
            double best = 1e300;
            for (const glm::dvec2& e : exits) best = std::min(best, glm::length(glm::dvec2(end) - e));
            EXPECT_LT(best, tol_px) << end.x << " " << end.y;
        }
}

// A seamount under the sea: z = -60 + 50 exp(-r^2 / (2 30^2)) (top 10 m under water, sides up to
// 40 degrees), seen from the south 10 degrees down. Without water its flanks make silhouettes;
// with the sea at 0 the surface over it is flat water: no silhouette pixel over it, and no shore.
TEST(Coastline, WaterHidesTheSeaFloor) {
    const Terrain t = terrain_from_function(161, 161, 5.0, [](double x, double y) {
        return -60.0 + 50.0 * std::exp(-(x * x + y * y) / (2.0 * 30.0 * 30.0));
    });
    const Camera cam = looking_north(250.0, -10.0, t);
    // the pixels over the seamount: the box of its projected foot and top
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const double x : {-90.0, 90.0})
        for (const double y : {-90.0, 90.0})
            for (const double z : {-60.0, -10.0, 0.0}) {
                const glm::dvec2 p = pixel_of(cam, {x, y, z});
                lo = glm::min(lo, p), hi = glm::max(hi, p);
            }
    const auto silhouette_pixels_over_it = [&](const PixelMask& m) {
        std::size_t n = 0;
        for (int y = std::max(0, int(lo.y)); y < std::min(m.height, int(hi.y) + 1); ++y)
            for (int x = std::max(0, int(lo.x)); x < std::min(m.width, int(hi.x) + 1); ++x)
                n += m.on[std::size_t(y) * m.width + x] != 0;
        return n;
    };
    TerrainFrames dry(test::test_context(), std::nullopt, Terrain(t), cam.width, cam.height, Log{});
    const SceneDrawing floor = dry.draw(cam, no_drainage());
    EXPECT_GT(silhouette_pixels_over_it(floor.silhouette_mask), 20u);
    TerrainFrames wet(test::test_context(), std::nullopt, with_sea(t, 0.0), cam.width, cam.height, Log{});
    const SceneDrawing water = wet.draw(cam, no_drainage());
    EXPECT_EQ(silhouette_pixels_over_it(water.silhouette_mask), 0u);
    EXPECT_TRUE(water.drawing.layer(LayerKind::coastline).strokes.empty());
    EXPECT_TRUE(floor.drawing.layer(LayerKind::coastline).strokes.empty());
}

// Creases and ridges on rough hills half drowned: with the sea at 150 m no vertex that the DM
// pass may draw (non-zero normal) lies at or below the water's drawn height (exaggeration 2),
// while without the sea some do (so the check can fail).
TEST(Coastline, NoCreaseOrRidgeOnWater) {
    const Terrain t = terrain_from_function(161, 161, 20.0, rough_hills);
    const DrainageDb db = drainage_lines_only(build_drainage_db(t, DrainageOptions{}));
    LineBox box = line_box(t);
    box.exaggeration = 2.0;
    const auto drawable_below = [](const ScoredLineSet& set, float z) {
        std::size_t n = 0, drawable = 0;
        for (std::size_t i = 0; i < set.positions.size(); ++i) {
            if (set.normals[i] == glm::vec3(0.0f)) continue;
            ++drawable;
            n += set.positions[i].z <= z;
        }
        EXPECT_GT(drawable, 100u);
        return n;
    };
    const DrainageLineData dry = prepare_drainage_lines(db, box);
    EXPECT_GT(drawable_below(dry.creases, 300.0f), 10u);
    EXPECT_GT(drawable_below(dry.ridges, 300.0f), 10u);
    box.sea_level = 150.0;
    const DrainageLineData wet = prepare_drainage_lines(db, box);
    EXPECT_EQ(drawable_below(wet.creases, 300.0f), 0u);
    EXPECT_EQ(drawable_below(wet.ridges, 300.0f), 0u);
}

namespace {
Scene scene_with(const test::TempDir& dir, const std::string& terrain_lines) {
    const std::string path = dir.file("s.toml");
    std::ofstream(path) << "[terrain]\ndem = \"x.asc\"\n" << terrain_lines;
    return load_scene(path);
}
std::string error_of(const test::TempDir& dir, const std::string& terrain_lines) {
    try {
        validate_scene(scene_with(dir, terrain_lines));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(SeaLevelScene, ReadValidatedAndStrict) {
    const test::TempDir dir;
    EXPECT_FALSE(scene_with(dir, "").terrain.sea_level.has_value());  // off by default
    EXPECT_EQ(scene_with(dir, "sea_level = 350\n").terrain.sea_level, 350.0);
    EXPECT_EQ(scene_with(dir, "sea_level = -2.5\n").terrain.sea_level, -2.5);
    const std::string f = dir.file("s.toml");
    EXPECT_EQ(error_of(dir, "sea_level = \"high\"\n"), "penink: scene: " + f + ": [terrain] sea_level: expected a number");
    EXPECT_EQ(error_of(dir, "sea_level = nan\n"), "penink: scene: " + f + ": [terrain] sea_level: expected a finite number");
    EXPECT_EQ(error_of(dir, "sea_level = 1e9\n"),
              "penink: scene: " + f + ": [terrain] sea_level must be between -1e+07 and 1e+07 metres (got 1e+09)");
    EXPECT_EQ(error_of(dir, "sealevel = 3\n"),
              "penink: scene: " + f + ": unknown key sealevel in [terrain]; did you mean sea_level?");
}
