// The scene file a preview saves: every key of the view reads back through load_scene exactly
// (numbers included), the base scene's other keys kept, its camera placement replaced; the
// page's JSON held to the scene's ranges; a pixel found on the ground through its depth.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <toml.hpp>

#include "core/camera.hpp"
#include "core/pixel_mask.hpp"
#include "preview/preview_session.hpp"
#include "preview/preview_view.hpp"
#include "scene/scene.hpp"

using namespace penink;
namespace fs = std::filesystem;

namespace {

Scene load_text(const std::string& text, const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("penink_preview_view_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path file = dir / name;
    std::ofstream(file) << text;
    Scene s = load_scene(file.string());
    validate_scene(s);
    fs::remove_all(dir);
    return s;
}

PreviewView odd_view() {
    PreviewView v;
    v.target_x = 588497.12345678901, v.target_y = 4589846.0000000037;
    v.distance = 1234.5678901234567;
    v.azimuth = 0.1 + 0.2, v.altitude = -33.333333333333336;
    v.fov = 41.7, v.width = 1200, v.height = 801;
    v.light_azimuth = 299.99999999999994, v.light_altitude = 12.5;
    v.vertical_exaggeration = 1.0 / 3.0;
    v.crease_min_score = -0.07, v.ridge_min_score = 0.3;
    v.hachure_spacing_min = 2.2, v.hachure_spacing_max = 17.5;
    v.style = "field-sketch";
    v.visible = {{"hachures", false}, {"ridges", true}};
    v.seed = 9007199254740991;
    v.sea_level = 350.25;
    return v;
}

}  // namespace

TEST(PreviewView, SceneTextReadsBackExactly) {
    const PreviewView v = odd_view();
    const std::string text = scene_text("", "/data/dem.tif", v);
    const Scene s = load_text(text, "view.toml");
    EXPECT_EQ(s.source.dem, "/data/dem.tif");
    ASSERT_TRUE(s.view.camera.target);
    EXPECT_EQ(*s.view.camera.target, toml_number(v.target_x) + " " + toml_number(v.target_y));
    EXPECT_EQ(std::strtod(s.view.camera.target->c_str(), nullptr), v.target_x);  // exact, not near
    EXPECT_FALSE(s.view.camera.position);
    EXPECT_EQ(s.view.camera.distance, v.distance);
    EXPECT_EQ(s.view.camera.azimuth, v.azimuth);
    EXPECT_EQ(s.view.camera.altitude, v.altitude);
    EXPECT_EQ(s.view.camera.fov, v.fov);
    EXPECT_EQ(s.view.camera.width, 1200);
    EXPECT_EQ(s.view.camera.height, 801);
    EXPECT_EQ(s.view.camera.projection, Projection::perspective);
    EXPECT_EQ(s.view.light.azimuth, v.light_azimuth);
    EXPECT_EQ(s.view.light.altitude, v.light_altitude);
    EXPECT_EQ(s.terrain.vertical_exaggeration, v.vertical_exaggeration);
    EXPECT_FALSE(s.terrain.exaggeration_auto);
    EXPECT_EQ(s.lines.creases.min_score, v.crease_min_score);
    EXPECT_EQ(s.lines.ridges.min_score, v.ridge_min_score);
    EXPECT_EQ(s.lines.hachures.spacing_min_px, v.hachure_spacing_min);
    EXPECT_EQ(s.lines.hachures.spacing_max_px, v.hachure_spacing_max);
    EXPECT_EQ(s.style.name, "field-sketch");
    EXPECT_EQ(s.style.seed, v.seed);
    ASSERT_TRUE(s.terrain.sea_level);
    EXPECT_EQ(*s.terrain.sea_level, 350.25);
    EXPECT_FALSE(s.style.resolved.layer(LayerKind::hachures).visible);
    EXPECT_TRUE(s.style.resolved.layer(LayerKind::ridges).visible);
    std::istringstream in(text);
    const toml::value style = toml::parse(in, "view.toml").at("style");
    EXPECT_FALSE(style.at("hachures").at("visible").as_boolean());
    EXPECT_FALSE(style.contains("ridges") && style.at("ridges").contains("visible"));
}

TEST(PreviewView, TheBaseSceneKeepsItsOtherKeys) {
    const std::string base = R"(
seed = 3
[terrain]
dem = "old.asc"
vertical_exaggeration = "auto"
[camera]
position = "1 2"
elevation = 500
width = 640
[silhouettes]
min_gap = 2.5
[creases]
slope_weight = 0.7
[style.creases]
width = 1.5
visible = false
)";
    PreviewView v = odd_view();
    v.visible = {{"creases", true}};
    v.sea_level.reset();
    const std::string saved = scene_text(base, "/abs/new.asc", v);
    const Scene s = load_text(saved, "kept.toml");
    EXPECT_EQ(s.source.dem, "/abs/new.asc");
    EXPECT_FALSE(s.view.camera.position);   // the view's target and distance place the camera
    EXPECT_FALSE(s.view.camera.elevation);
    EXPECT_EQ(s.view.camera.width, 1200);
    EXPECT_EQ(s.lines.silhouette_min_gap, 2.5f);
    EXPECT_EQ(s.lines.creases.slope_weight, 0.7);
    EXPECT_EQ(s.lines.creases.min_score, v.crease_min_score);
    EXPECT_EQ(s.style.resolved.layer(LayerKind::creases).width, 1.5);
    EXPECT_TRUE(s.style.resolved.layer(LayerKind::creases).visible);  // shown again
    std::istringstream in(saved);
    const toml::value creases = toml::parse(in, "kept.toml").at("style").at("creases");
    EXPECT_EQ(creases.at("width").as_floating(), 1.5);
    EXPECT_FALSE(creases.contains("visible"));
    EXPECT_FALSE(s.terrain.sea_level);
    EXPECT_EQ(s.style.seed, v.seed);
}

TEST(PreviewView, OrthographicViewsAreCentredOnTheTarget) {
    PreviewView v = odd_view();
    v.orthographic = true, v.altitude = -90.0, v.map_scale = 25000.0;
    const Scene s = load_text(scene_text("", "/d.tif", v), "map.toml");
    EXPECT_EQ(s.view.camera.projection, Projection::orthographic);
    EXPECT_TRUE(s.view.camera.target);
    EXPECT_FALSE(s.view.camera.distance);
    EXPECT_EQ(s.view.map_scale, 25000.0);
}

TEST(PreviewView, NumbersAreTheShortestExactText) {
    for (double x : {0.1, 1.0 / 3.0, 1e-300, 123456789.0, -0.0, 5e22, 2.5})
        EXPECT_EQ(std::strtod(toml_number(x).c_str(), nullptr), x) << toml_number(x);
    EXPECT_EQ(toml_number(2.5), "2.5");
    EXPECT_EQ(toml_number(3.0), "3.0");  // a float to TOML, not an integer
    EXPECT_EQ(toml_number(0.1), "0.1");
}

TEST(PreviewView, JsonChangesOnlyWhatItNames) {
    const PreviewView v = odd_view();
    const PreviewView w = view_from_json(nlohmann::json{{"azimuth", 10.5}, {"layers", {{"creases", false}}}}, v);
    EXPECT_EQ(w.azimuth, 10.5);
    EXPECT_EQ(w.altitude, v.altitude);
    EXPECT_FALSE(w.visible.at("creases"));
    EXPECT_EQ(view_from_json(view_json(v), v).distance, v.distance);  // the page's copy reads back
}

TEST(PreviewView, JsonOutOfRangeIsRefused) {
    const PreviewView v = odd_view();
    using nlohmann::json;
    EXPECT_THROW(view_from_json(json{{"altitude", -91}}, v), std::invalid_argument);
    EXPECT_THROW(view_from_json(json{{"light_altitude", -1}}, v), std::invalid_argument);  // a sun below the horizon
    EXPECT_THROW(view_from_json(json{{"width", 100000}}, v), std::invalid_argument);
    EXPECT_THROW(view_from_json(json{{"distance", 0}}, v), std::invalid_argument);
    EXPECT_THROW(view_from_json(json{{"azimuth", "north"}}, v), std::invalid_argument);
    EXPECT_THROW(view_from_json(json{{"layers", {{"nonsense", true}}}}, v), std::invalid_argument);
    EXPECT_THROW(view_from_json(json{{"hachure_spacing_max", 1.0}}, v), std::invalid_argument);  // under the min
    EXPECT_THROW(view_from_json(json::array(), v), std::invalid_argument);
}

TEST(PreviewView, APixelIsFoundOnTheGroundThroughItsDepth) {
    for (Projection projection : {Projection::perspective, Projection::orthographic}) {
        Camera cam;
        cam.projection = projection;
        cam.eye = {100.0, -300.0, 400.0};
        cam.azimuth = 30.0, cam.altitude = -35.0, cam.fov = 50.0, cam.view_width = 600.0;
        cam.width = 320, cam.height = 200, cam.near_plane = 1.0, cam.far_plane = 5000.0;
        const glm::dvec3 ground{250.0, 20.0, 35.0};
        glm::dvec2 pixel;
        double depth = 0.0;
        ASSERT_TRUE(project_to_pixel(cam, ground, pixel, depth));
        DepthImage image{cam.width, cam.height, std::vector<float>(std::size_t(cam.width) * cam.height, INFINITY)};
        const int x = int(pixel.x), y = int(pixel.y);
        image.depth[std::size_t(y) * cam.width + x] = float(depth);
        const auto p = unproject_pixel(cam, image, pixel.x, pixel.y);
        ASSERT_TRUE(p);
        // the pixel centre's ray, not the point's own: within a pixel's width at that depth
        EXPECT_LT(glm::length(*p - ground), 1.5 * world_per_pixel(cam, depth)) << int(projection);
        EXPECT_NEAR(eye_depth(cam, *p), depth, 1e-3 * depth);
        EXPECT_FALSE(unproject_pixel(cam, image, 5.0, 5.0));  // sky
        EXPECT_FALSE(unproject_pixel(cam, image, -1.0, 5.0));
    }
}
