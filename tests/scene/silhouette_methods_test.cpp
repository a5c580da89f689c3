// Accuracy of the four silhouette methods (Toward/Away, Adjacency, edge walk, object-space) on analytic
// terrains with closed-form silhouettes (input/analytic_terrain.hpp), scored with
// lines/line_accuracy.hpp against the visible silhouette with terrain behind it (the part a
// depth-image method can see; the outline against the sky is traced from the surface mask).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "input/analytic_terrain.hpp"
#include "lines/line_accuracy.hpp"
#include "lines/object_silhouettes.hpp"
#include "core/error.hpp"
#include "core/stopwatch.hpp"
#include "render/terrain_renderer.hpp"
#include "scene/scene.hpp"
#include "scene/terrain_frames.hpp"
#include "surface/pn_tessellation.hpp"

using namespace penink;

namespace {

struct Case {
    AnalyticTerrain shape;
    double spacing;
    Camera cam;
};

Camera camera(glm::dvec3 eye, double azimuth, double altitude, double fov, const AnalyticTerrain& s) {
    Camera c;
    c.eye = eye, c.azimuth = azimuth, c.altitude = altitude, c.fov = fov;
    c.width = 400, c.height = 300;
    const double top = s.shape == AnalyticShape::hemisphere ? s.width : s.height;
    fit_depth_range(c, {-s.half_extent, -s.half_extent, 0.0}, {s.half_extent, s.half_extent, top});
    return c;
}

Case hill_case() {
    AnalyticTerrain s;  // 250 m high, sigma 150 m, on a 4 km square (as sil_accuracy_test)
    return {s, 25.0, camera({0.0, -1300.0, 450.0}, 0.0, -10.0, 40.0, s)};
}

Case sphere_case() {
    AnalyticTerrain s;
    s.shape = AnalyticShape::hemisphere, s.width = 200.0, s.half_extent = 1000.0;
    return {s, 10.0, camera({0.0, -700.0, 260.0}, 0.0, -14.0, 60.0, s)};
}

Case ridge_case() {
    AnalyticTerrain s;
    s.shape = AnalyticShape::ridge, s.height = 150.0, s.width = 120.0, s.half_extent = 1000.0;
    return {s, 20.0, camera({0.0, -1100.0, 170.0}, 0.0, -5.0, 60.0, s)};
}

Case cliff_case() {  // from the high side, above the plateau: the top edge is the silhouette
    AnalyticTerrain s;
    s.shape = AnalyticShape::cliff, s.height = 100.0, s.half_extent = 1000.0;
    return {s, 20.0, camera({0.0, -700.0, 300.0}, 0.0, -15.0, 60.0, s)};
}

struct Scored {
    LineAccuracy acc;
    double ms, ids_ms;
};

Scored run(const Case& c, SilhouetteMethod method, const std::vector<ImagePolyline>& ref, int walk_rounds = 32) {
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    TerrainRenderer renderer(test::test_context().gl(), mesh, c.cam.width, c.cam.height);
    FrameOptions options;
    options.silhouette_method = method;
    options.edge_walk.walk_rounds = walk_rounds;
    renderer.render(c.cam, options);  // warm-up: program JIT
    FrameImages img = renderer.render(c.cam, options);
    if (method == SilhouetteMethod::object_space) {  // drawn on the CPU by the scene layer
        const auto t0 = Clock::now();
        img.silhouettes = object_space_silhouette_mask(mesh, c.cam, options.tessellation);
        img.times.sil = ms_since(t0);
    }
    return {line_accuracy(img.silhouettes, ref, {1.0, 1.5, 2.0}), img.times.sil, img.times.sil_ids};
}

void report(const char* name, const char* method, const Scored& s) {
    std::printf("%-10s %-12s P1 %.3f R1 %.3f P1.5 %.3f R1.5 %.3f P2 %.3f R2 %.3f  d->r %.2f r->d %.2f px  sil %.1f ms (ID pass %.1f)\n",
                name, method, s.acc.at(1.0).precision, s.acc.at(1.0).recall, s.acc.at(1.5).precision,
                s.acc.at(1.5).recall, s.acc.at(2.0).precision, s.acc.at(2.0).recall,
                s.acc.mean_drawn_to_reference, s.acc.mean_reference_to_drawn, s.ms, s.ids_ms);
}

// The analytic reference of a case and the three methods scored against it, each reported.
struct Methods {
    std::vector<ImagePolyline> ref;
    Scored ta, adj, walk, obj;
};

Methods run_methods(const Case& c, const char* name) {
    Methods m;
    m.ref = analytic_silhouettes(c.shape, c.cam, true);
    m.ta = run(c, SilhouetteMethod::toward_away, m.ref);
    m.adj = run(c, SilhouetteMethod::adjacency, m.ref);
    m.walk = run(c, SilhouetteMethod::edge_walk, m.ref);
    m.obj = run(c, SilhouetteMethod::object_space, m.ref);
    report(name, "toward-away", m.ta), report(name, "adjacency", m.adj), report(name, "edge-walk", m.walk);
    report(name, "object", m.obj);
    return m;
}

}  // namespace

// Measured here (llvmpipe, 400x300, default tessellation 8 px / max 16), precision / recall:
//            Toward/Away        Adjacency          edge walk          object-space
// hill  1.5px 0.944 / 0.994     0.673 / 0.994      0.911 / 1.000      0.912 / 1.000
// cliff 1px   1.000 / 1.000     0.367 / 1.000      1.000 / 1.000      1.000 / 1.000
// sphere 1.5px 0.410 / 1.000    0.226 / 1.000      0.335 / 1.000      0.437 / 1.000  (low precision: the mesh's
//             smoothed hemisphere-plane crease has silhouettes the sharp analytic one lacks)
// ridge 2px   0.691 / 1.000     0.362 / 1.000      0.468 / 1.000      0.606 / 1.000
// Adjacency (the paper's ID-raster test) finds the contour (recall as Toward/Away's) but also
// marks pixel pairs across a triangle thinner than a pixel (no contact between the two sampled
// triangles) wherever the surface turns away nearby, so its precision is the lowest.
// The edge walk draws the tessellated mesh's contour edges (found on the ID raster, continued by
// the contour walk) as lines, so it follows the object-space reference; without the walk (only
// pairs the raster sampled) the hill's recall at 1.5 px was 0.37.

TEST(SilhouetteMethods, GaussianHillAtGrazingView) {
    const Case c = hill_case();
    const auto [ref, ta, adj, walk, obj] = run_methods(c, "hill");
    EXPECT_GT(ta.acc.reference_length, 200.0);
    EXPECT_GE(ta.acc.at(1.5).recall, 0.95);
    EXPECT_GE(ta.acc.at(1.5).precision, 0.90);
    EXPECT_GE(obj.acc.at(1.0).recall, 0.99);  // the tessellated surface's exact contour
    EXPECT_GE(obj.acc.at(1.5).precision, 0.88);
    EXPECT_GE(walk.acc.at(1.5).precision, 0.88);
    EXPECT_GE(walk.acc.at(1.5).recall, 0.97);
    EXPECT_LT(walk.acc.mean_reference_to_drawn, 0.6);
    // The paper's Adjacency: the contour within 1.5 px as Toward/Away finds it (0.994 measured);
    // precision 0.673 measured (pairs across sub-pixel triangles near the contour).
    EXPECT_GE(adj.acc.at(1.5).recall, 0.97);
    EXPECT_GE(adj.acc.at(1.5).precision, 0.6);
    const Scored raster_only = run(c, SilhouetteMethod::edge_walk, ref, 0);  // no contour walk
    report("hill", "edge-no-walk", raster_only);
    EXPECT_LT(raster_only.acc.at(1.5).recall, 0.6);  // thin contour triangles: few pairs sampled
}

TEST(SilhouetteMethods, CliffTopSeenFromTheHighSide) {
    const Case c = cliff_case();
    const auto [ref, ta, adj, walk, obj] = run_methods(c, "cliff");
    EXPECT_NEAR(ta.acc.reference_length, 400.0, 1.0);  // the edge crosses the whole image
    EXPECT_GE(ta.acc.at(1.0).recall, 0.99);
    EXPECT_GE(ta.acc.at(1.0).precision, 0.99);
    EXPECT_GE(obj.acc.at(1.0).recall, 0.99);
    EXPECT_GE(obj.acc.at(1.0).precision, 0.99);
    EXPECT_GE(walk.acc.at(1.0).precision, 0.99);
    EXPECT_GE(walk.acc.at(1.0).recall, 0.98);
    EXPECT_GE(adj.acc.at(1.0).recall, 0.99);
}

TEST(SilhouetteMethods, HemisphereBump) {
    const Case c = sphere_case();
    const auto [ref, ta, adj, walk, obj] = run_methods(c, "sphere");
    EXPECT_GT(ta.acc.reference_length, 150.0);
    EXPECT_GE(ta.acc.at(1.5).recall, 0.97);
    EXPECT_GE(walk.acc.at(1.5).recall, 0.97);
    EXPECT_GE(walk.acc.at(1.5).precision, 0.30);
    EXPECT_GE(adj.acc.at(1.5).recall, 0.97);
    EXPECT_GE(obj.acc.at(1.0).recall, 0.99);
}

TEST(SilhouetteMethods, RidgeSeenEdgeOn) {
    const Case c = ridge_case();
    const auto [ref, ta, adj, walk, obj] = run_methods(c, "ridge");
    EXPECT_GT(ta.acc.reference_length, 100.0);
    EXPECT_GE(ta.acc.at(2.0).recall, 0.9);
    EXPECT_GE(walk.acc.at(2.0).recall, 0.95);
    EXPECT_GE(walk.acc.at(2.0).precision, 0.42);
    EXPECT_GE(adj.acc.at(2.0).recall, 0.95);
    EXPECT_GE(obj.acc.at(2.0).recall, 0.9);
}

TEST(SilhouetteMethods, ObjectSpaceReferenceMatchesAnalyticHill) {
    // CPU tessellation + exact ray casts, no GPU: the tessellated surface's visible contour with
    // terrain behind against the closed form.
    const Case c = hill_case();
    const SurfaceMesh mesh = mesh_from_terrain(analytic_grid(c.shape, c.spacing));
    const PnTessellation t = tessellate_pn_surface(mesh, view_projection(c.cam), {400.0f, 300.0f}, 8.0f, 16);
    const ObjectSilhouettes sil = object_space_silhouettes(t.pos, t.tri, c.cam);
    const auto lines = silhouette_polylines(sil, true);
    const LineAccuracy a = line_accuracy(rasterize_polylines(lines, 400, 300), analytic_silhouettes(c.shape, c.cam, true),
                                         {1.0, 2.0});
    EXPECT_GT(sil.silhouette_edges, 100u);
    EXPECT_GE(a.at(1.0).recall, 0.99);
    EXPECT_LT(a.mean_reference_to_drawn, 0.6);
}


// Scene names: "adjacency" is the paper's ID-raster algorithm (3.1), "edge-walk" penink's
// contour-edge method; an unknown name is a one-line error listing the four.
TEST(SilhouetteMethods, SceneNames) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "penink_silhouette_names";
    std::filesystem::create_directories(dir);
    auto load = [&](const std::string& method) {
        const std::string file = (dir / "scene.toml").string();
        std::ofstream(file) << "[terrain]\ndem = \"" PENINK_SOURCE_DIR "/examples/volcano.asc\"\n[silhouettes]\nmethod = \""
                            << method << "\"\n";
        return load_scene(file).lines.silhouette_method;
    };
    EXPECT_EQ(load("adjacency"), SilhouetteMethod::adjacency);
    EXPECT_EQ(load("edge-walk"), SilhouetteMethod::edge_walk);
    EXPECT_EQ(load("toward-away"), SilhouetteMethod::toward_away);
    EXPECT_EQ(load("object-space"), SilhouetteMethod::object_space);
    for (SilhouetteMethod m : {SilhouetteMethod::toward_away, SilhouetteMethod::adjacency, SilhouetteMethod::edge_walk,
                               SilhouetteMethod::object_space})
        EXPECT_EQ(silhouette_method_named(silhouette_method_name(m)), m);
    try {
        load("walk");
        FAIL() << "unknown method accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("\"toward-away\", \"adjacency\", \"edge-walk\" or \"object-space\" (got \"walk\")"),
                  std::string::npos)
            << e.what();
    }
    std::filesystem::remove_all(dir);
}
