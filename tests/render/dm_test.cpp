// DM pass: the terms it writes for vertices on a tilted plane (sc = 1 - n.z, ic = 1 - n.l, the
// vertex's flow, its eye distance d) equal their closed form computed on the CPU; vertices behind
// a ridge (occlusion found by marching the eye ray against the analytic height) come back hidden,
// those in front visible; vertices outside the frustum hidden; scored by crease_scores
// (lines/crease_scores.hpp), min_score and distance_attenuation act as eq. 6 says.
#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "support/synthetic_terrain.hpp"
#include "lines/crease_scores.hpp"
#include "render/dm.hpp"
#include "render/terrain_renderer.hpp"

using namespace penink;

namespace {

constexpr double slope = 0.5;  // z = slope * x: normal (-slope, 0, 1) / |.|

double plane(double x, double) { return slope * x; }

// Gaussian ridge along x at y = 0 on flat ground.
constexpr double ridge_h = 300.0, ridge_w = 60.0;
double ridge(double, double y) { return ridge_h * std::exp(-y * y / (2.0 * ridge_w * ridge_w)); }
glm::vec3 ridge_normal(double y) {
    const double dz_dy = -ridge(0.0, y) * y / (ridge_w * ridge_w);
    return glm::vec3(glm::normalize(glm::dvec3(0.0, -dz_dy, 1.0)));
}

Camera north_camera(double eye_z, double altitude) {
    Camera cam;
    cam.eye = {0.0, -1200.0, eye_z};
    cam.azimuth = 0.0, cam.altitude = altitude, cam.fov = 50.0;
    cam.width = 320, cam.height = 240;
    fit_depth_range(cam, {-1000.0, -1000.0, -600.0}, {1000.0, 1000.0, 600.0});
    return cam;
}

// Pixel of `p` at least `margin` pixels inside the image (and in front of the eye).
bool inside_by(const Camera& cam, const glm::vec3& p, double margin) {
    glm::dvec2 px;
    double depth;
    if (!project_to_pixel(cam, glm::dvec3(p), px, depth)) return false;
    return px.x >= margin && px.y >= margin && px.x <= cam.width - margin && px.y <= cam.height - margin;
}

// Flow in [0, 1) from the vertex index (splitmix64 bits).
float flow_of(std::uint64_t i) {
    std::uint64_t z = (i + 1) * 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return float((z ^ (z >> 31)) >> 40) / float(1 << 24);
}

struct PlaneScene {
    SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(81, 81, 10.0, plane));
    Camera cam = north_camera(700.0, -30.0);
    std::vector<DmVertex> vertices;
    glm::dvec3 light = glm::normalize(glm::dvec3(-0.8, 0.3, 0.5));
    PlaneScene() {
        const glm::vec3 n(glm::normalize(glm::dvec3(-slope, 0.0, 1.0)));
        for (double y = -399.0; y <= 399.0; y += 21.0)  // up to 1 m from the DEM's edges
            for (double x = -399.0; x <= 399.0; x += 21.0) {
                DmVertex v;
                v.position = glm::vec3(float(x), float(y), float(plane(x, y)));
                v.normal = n, v.flow = flow_of(vertices.size());
                vertices.push_back(v);
            }
        for (int k = 0; k < 30; ++k) {  // left, right of the frustum and behind the eye
            const double y = -300.0 + 20.0 * k;
            for (const glm::dvec3 p : {glm::dvec3(-2500.0, y, 0.0), glm::dvec3(2500.0, y, 0.0),
                                       glm::dvec3(y, -1500.0, 800.0)}) {
                DmVertex v;
                v.position = glm::vec3(p);
                v.normal = n, v.flow = 1.0f;
                vertices.push_back(v);
            }
        }
    }
};

// A DmVertex list as the pass reads it (DmInput: positions, normals and flow), kept alive here.
struct DmArrays {
    std::vector<glm::vec3> positions, normals;
    std::vector<float> flow;
    explicit DmArrays(const std::vector<DmVertex>& v) {
        for (const DmVertex& d : v) positions.push_back(d.position), normals.push_back(d.normal), flow.push_back(d.flow);
    }
    DmInput input() const { return {positions, normals, flow}; }
};

std::vector<CreaseTerms> run_terms(const PlaneScene& s, TerrainRenderer& r) {
    const DmArrays arrays(s.vertices);
    DmPass pass(test::test_context().gl(), arrays.input());
    DmFrame f;
    f.camera = &s.cam, f.light = glm::vec3(s.light);
    f.toward_texture = r.surface_pass().toward_texture();
    std::vector<CreaseTerms> terms;
    pass.run(f, terms);
    EXPECT_EQ(terms.size(), s.vertices.size());
    return terms;
}

std::vector<float> run_dm(const PlaneScene& s, TerrainRenderer& r, float D, const CreaseParams& score) {
    return crease_scores(run_terms(s, r), score, D);
}

}  // namespace

// sc, ic and fc are computed in float from float normals: 1e-5 is a few float ulps of a term in
// [0, 1]. d is ~1-2 km from float positions (ulp ~1e-4 m): 1e-2 m.
TEST(DmPass, TiltedPlaneTermsMatchClosedForm) {
    const PlaneScene s;
    TerrainRenderer renderer(test::test_context().gl(), s.mesh, s.cam.width, s.cam.height);
    renderer.render(s.cam, {});
    const std::vector<CreaseTerms> terms = run_terms(s, renderer);
    std::size_t checked = 0, outside = 0;
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        const DmVertex& v = s.vertices[i];
        if (inside_by(s.cam, v.position, 2.0)) {
            ASSERT_NE(terms[i].distance, dm_hidden) << "vertex " << i << " on the plane in view is hidden";
            const glm::dvec3 n(v.normal);
            EXPECT_NEAR(terms[i].slope, 1.0 - n.z, 1e-5) << i;
            EXPECT_NEAR(terms[i].illumination, 1.0 - std::clamp(glm::dot(n, s.light), 0.0, 1.0), 1e-5) << i;
            EXPECT_EQ(terms[i].flow, v.flow) << i;
            EXPECT_NEAR(terms[i].distance, glm::length(glm::dvec3(v.position) - s.cam.eye), 1e-2) << i;
            ++checked;
        } else if (!inside_by(s.cam, v.position, -2.0)) {
            EXPECT_EQ(terms[i].distance, dm_hidden) << "vertex " << i << " outside the frustum";
            ++outside;
        }
    }
    EXPECT_GT(checked, 300u);
    EXPECT_GT(outside, 20u);
}

TEST(DmPass, MinScoreAndAttenuationActAsTheFormulaSays) {
    const PlaneScene s;
    TerrainRenderer renderer(test::test_context().gl(), s.mesh, s.cam.width, s.cam.height);
    const FrameImages img = renderer.render(s.cam, {});
    const float D = max_visible_distance(img.toward);
    CreaseParams score{2.0f, 0.5f, 4.0f, 0.0f, 0.0f};
    const std::vector<float> base = run_dm(s, renderer, D, score);
    std::size_t previous = s.vertices.size() + 1;
    std::vector<std::size_t> counts;
    for (float min_score : {-0.5f, 0.1f, 0.3f, 0.5f, 0.7f, 0.9f, 1.5f}) {
        score.min_score = min_score;
        const std::vector<float> sc = run_dm(s, renderer, D, score);
        std::size_t n = 0;
        for (std::size_t i = 0; i < sc.size(); ++i) {
            n += sc[i] >= 0.0f;
            if (base[i] != dm_hidden) {
                EXPECT_NEAR(sc[i], base[i] - min_score, 1e-5);
            }
        }
        EXPECT_LE(n, previous) << "min_score " << min_score;
        RecordProperty("drawn_at_min_score_" + std::to_string(int(min_score * 10)), int(n));
        previous = n;
        counts.push_back(n);
    }
    EXPECT_GT(counts.front(), 300u);  // everything visible scores >= -0.5 + 0
    EXPECT_EQ(counts.back(), 0u);     // (2 sc + 0.5 ic + 4 fc) / 3 < 1.5 here
    EXPECT_GT(counts[2], counts[4]);  // strictly fewer somewhere in between
    // Attenuation lowers each score by attenuation * d / D: far ones more than near ones.
    score.min_score = 0.0f, score.distance_attenuation = 0.5f;
    const std::vector<float> att = run_dm(s, renderer, D, score);
    double near_drop = 1e9, far_drop = 0.0, near_d = 1e9, far_d = 0.0;
    for (std::size_t i = 0; i < att.size(); ++i) {
        if (base[i] == dm_hidden) continue;
        const double d = glm::length(glm::dvec3(s.vertices[i].position) - s.cam.eye), drop = base[i] - att[i];
        EXPECT_NEAR(drop, 0.5 * d / D, 1e-5);
        if (d < near_d) near_d = d, near_drop = drop;
        if (d > far_d) far_d = d, far_drop = drop;
    }
    EXPECT_GT(far_d, near_d * 1.4);
    EXPECT_GT(far_drop, near_drop * 1.4);
}

TEST(DmPass, VerticesBehindARidgeAreHidden) {
    GlContext& ctx = test::test_context();
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(161, 161, 10.0, ridge));
    const Camera cam = north_camera(400.0, -12.0);
    TerrainRenderer renderer(ctx.gl(), mesh, cam.width, cam.height);
    renderer.render(cam, {});
    std::vector<DmVertex> vertices;
    for (double y = -700.0; y <= 790.0; y += 20.0)
        for (double x = -300.0; x <= 300.0; x += 50.0) {
            DmVertex v;
            v.position = glm::vec3(float(x), float(y), float(ridge(x, y)));
            v.normal = ridge_normal(y), v.flow = 0.5f;
            vertices.push_back(v);
        }
    const DmArrays arrays(vertices);
    DmPass pass(ctx.gl(), arrays.input());
    DmFrame f;
    f.camera = &cam;
    f.toward_texture = renderer.surface_pass().toward_texture();
    std::vector<CreaseTerms> terms;
    pass.run(f, terms);
    std::vector<float> scores(terms.size());  // the distances: dm_hidden where hidden
    for (std::size_t i = 0; i < terms.size(); ++i) scores[i] = terms[i].distance;
    // March the eye ray: hidden when the ridge rises >= 5 m above it at least 80 m before the
    // vertex, visible when the ray stays >= 2 m above the ground until 10 m before it.
    std::size_t hidden = 0, visible = 0;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const glm::dvec3 p(vertices[i].position), e = cam.eye;
        if (!inside_by(cam, vertices[i].position, 2.0)) continue;
        const double len = glm::length(p - e);
        double clear = 1e9, block = -1e9;
        for (double t = 0.0; t < len - 10.0; t += 1.0) {
            const glm::dvec3 q = e + (p - e) * (t / len);
            const double above = q.z - ridge(q.x, q.y);
            clear = std::min(clear, above);
            if (t < len - 80.0) block = std::max(block, -above);
        }
        if (block >= 5.0) {
            EXPECT_EQ(scores[i], dm_hidden) << "occluded vertex y " << p.y << " x " << p.x;
            ++hidden;
        } else if (clear >= 2.0) {
            EXPECT_NE(scores[i], dm_hidden) << "visible vertex y " << p.y << " x " << p.x;
            ++visible;
        }
    }
    RecordProperty("occluded", int(hidden));
    RecordProperty("visible", int(visible));
    EXPECT_GT(hidden, 100u);
    EXPECT_GT(visible, 100u);
    // The crest (y = 0) is on the skyline: the lift takes it off the outline, it stays drawn.
    std::size_t crest = 0;
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if (vertices[i].position.y == 0.0f && inside_by(cam, vertices[i].position, 2.0)) {
            EXPECT_NE(scores[i], dm_hidden) << "crest x " << vertices[i].position.x;
            ++crest;
        }
    EXPECT_GE(crest, 10u);
}

TEST(DmPass, ZeroNormalMeansOffSurfaceAndHidden) {
    const PlaneScene s;
    TerrainRenderer renderer(test::test_context().gl(), s.mesh, s.cam.width, s.cam.height);
    const FrameImages img = renderer.render(s.cam, {});
    PlaneScene off = s;
    for (std::size_t i = 0; i < off.vertices.size(); i += 2) off.vertices[i].normal = glm::vec3(0.0f);
    const std::vector<float> scores = run_dm(off, renderer, max_visible_distance(img.toward), CreaseParams{});
    std::size_t drawn = 0;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        if (i % 2 == 0) {
            EXPECT_EQ(scores[i], dm_hidden) << i;
        }
        drawn += i % 2 == 1 && scores[i] != dm_hidden;
    }
    EXPECT_GT(drawn, 300u);
}

TEST(DmPass, EmptyVertexSetReturnsNoScores) {
    const PlaneScene s;
    TerrainRenderer renderer(test::test_context().gl(), s.mesh, s.cam.width, s.cam.height);
    renderer.render(s.cam, {});
    DmPass pass(test::test_context().gl(), DmInput{});
    DmFrame f;
    f.camera = &s.cam, f.toward_texture = renderer.surface_pass().toward_texture();
    std::vector<CreaseTerms> terms(5);
    pass.run(f, terms);
    EXPECT_TRUE(terms.empty());
    EXPECT_EQ(pass.size(), 0u);
}

// The vertices are laid out on the GPU a chunk at a time: 2.3 chunks of the plane's vertices
// repeated score as the plane's own, each at its place (a chunk written at a wrong offset, or
// short, would move or zero the terms after it); flow left out counts as 0.
TEST(DmPass, VerticesLaidOutAChunkAtATimeKeepTheirPlaces) {
    const PlaneScene s;
    TerrainRenderer renderer(test::test_context().gl(), s.mesh, s.cam.width, s.cam.height);
    renderer.render(s.cam, {});
    const std::vector<CreaseTerms> one = run_terms(s, renderer);
    const DmArrays arrays(s.vertices);
    DmArrays many(std::vector<DmVertex>{});
    while (many.positions.size() < 150000)
        for (std::size_t i = 0; i < arrays.positions.size(); ++i)
            many.positions.push_back(arrays.positions[i]), many.normals.push_back(arrays.normals[i]),
                many.flow.push_back(arrays.flow[i]);
    DmFrame f;
    f.camera = &s.cam, f.light = glm::vec3(s.light);
    f.toward_texture = renderer.surface_pass().toward_texture();
    DmPass pass(test::test_context().gl(), many.input());
    std::vector<CreaseTerms> terms;
    pass.run(f, terms);
    ASSERT_EQ(terms.size(), many.positions.size());
    std::size_t visible = 0;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const CreaseTerms& a = terms[i], &b = one[i % one.size()];
        ASSERT_EQ(a.distance, b.distance) << i;
        ASSERT_EQ(a.slope, b.slope) << i;
        ASSERT_EQ(a.illumination, b.illumination) << i;
        ASSERT_EQ(a.flow, b.flow) << i;
        visible += a.distance != dm_hidden;
    }
    EXPECT_GT(visible, terms.size() / 2);
    pass.set_vertices(DmInput{many.positions, many.normals, {}});
    pass.run(f, terms);
    ASSERT_EQ(terms.size(), many.positions.size());
    for (std::size_t i = 0; i < terms.size(); ++i) {
        if (terms[i].distance == dm_hidden) continue;
        ASSERT_EQ(terms[i].flow, 0.0f) << i;
        ASSERT_EQ(terms[i].slope, one[i % one.size()].slope) << i;
    }
    EXPECT_THROW(pass.set_vertices(DmInput{many.positions, arrays.normals, {}}), std::invalid_argument);
}
