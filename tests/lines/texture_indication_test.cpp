// Indication textures: library loading, Perlin noise, placement on a small "building on a lawn"
// (clipped to the faces, denser near feature edges, threshold response, determinism).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "lines/indication_textures.hpp"

using namespace penink;

namespace {

const std::string kLib = PENINK_SOURCE_DIR "/examples/textures";

void quad(TriangleMesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, unsigned mat) {
    unsigned i = unsigned(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c, d});
    m.triangles.emplace_back(i, i + 1, i + 2);
    m.triangles.emplace_back(i, i + 2, i + 3);
    m.material.insert(m.material.end(), {mat, mat});
}

// A 4 x 4 x 3 m brick block (walls + roof, z up) on a 12 x 12 m lawn split in 4 quads.
TriangleMesh block_on_lawn() {
    TriangleMesh m;
    m.material_names = {"walls", "ground", "roof"};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            float x0 = -6.0f + 6 * i, y0 = -6.0f + 6 * j;
            quad(m, {x0, y0, 0}, {x0 + 6, y0, 0}, {x0 + 6, y0 + 6, 0}, {x0, y0 + 6, 0}, 1);
        }
    glm::vec3 c[8];
    for (int k = 0; k < 8; ++k) c[k] = glm::vec3(k & 1 ? 2 : -2, k & 2 ? 2 : -2, k & 4 ? 3 : 0);
    quad(m, c[0], c[1], c[5], c[4], 0);  // south
    quad(m, c[1], c[3], c[7], c[5], 0);  // east
    quad(m, c[3], c[2], c[6], c[7], 0);  // north
    quad(m, c[2], c[0], c[4], c[6], 0);  // west
    quad(m, c[4], c[5], c[7], c[6], 2);  // roof
    return m;
}

TextureOptions house_style(float threshold, std::uint64_t seed) {
    TextureOptions o;
    o.materials["walls"] = {"bricks", 1.0f, 0.6f};
    o.materials["ground"] = {"grass", 1.0f, 0.5f};
    o.materials["roof"] = {"shingles", 1.0f, 0.8f};
    o.threshold = threshold;
    o.seed = seed;
    return o;
}

float distance_to_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    glm::vec3 q = p - glm::dot(p - a, n) * n;
    float e = 1e-4f;
    bool inside = glm::dot(glm::cross(b - a, q - a), n) >= -e && glm::dot(glm::cross(c - b, q - b), n) >= -e &&
                  glm::dot(glm::cross(a - c, q - c), n) >= -e;
    return inside ? std::abs(glm::dot(p - a, n)) : 1e30f;
}

bool on_mesh(const TriangleMesh& m, const glm::vec3& p) {
    for (const auto& t : m.triangles)
        if (distance_to_triangle(p, m.positions[t.x], m.positions[t.y], m.positions[t.z]) < 1e-4f) return true;
    return false;
}

std::size_t point_count(const std::vector<ObjectPolyline>& lines) {
    std::size_t n = 0;
    for (const auto& l : lines) n += l.points.size();
    return n;
}

}  // namespace

TEST(TextureLibrary, ShipsTheFiveTexturesWithVariants) {
    TextureLibrary lib = load_texture_library(kLib);
    for (const char* name : {"bricks", "stone", "shingles", "grass", "hatching"}) {
        ASSERT_TRUE(lib.textures.count(name)) << name;
        EXPECT_GE(lib.textures.at(name).size(), 3u) << name;
        for (const auto& cluster : lib.textures.at(name))
            for (const auto& stroke : cluster)
                for (const auto& p : stroke) {
                    EXPECT_GE(std::min(p.x, p.y), 0.0f);
                    EXPECT_LE(std::max(p.x, p.y), 1.0f);
                }
    }
}

TEST(TextureLibrary, ErrorsAreExact) {
    try {
        load_texture_library("/nonexistent/dir");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: textures: /nonexistent/dir: no texture library here");
    }
    std::string dir = testing::TempDir() + "/penink_texlib";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/bad.txt") << "variant\n0.1 0.2 0.3\n";
    try {
        load_texture_library(dir);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: textures: " + dir + "/bad.txt: odd number of coordinates");
    }
    std::ofstream(dir + "/bad.txt") << "0.1 0.2 1.5 0.3\n";
    try {
        load_texture_library(dir);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: textures: " + dir + "/bad.txt: coordinate outside the unit square");
    }
}

TEST(Perlin, ZeroOnLatticeBoundedAndSeeded) {
    PerlinNoise a = make_perlin(7), b = make_perlin(7), c = make_perlin(8);
    EXPECT_EQ(a.perm, b.perm);
    EXPECT_NE(a.perm, c.perm);
    EXPECT_DOUBLE_EQ(perlin3(a, 1.0, 2.0, 3.0), 0.0);
    double lo = 0, hi = 0, diff = 0;
    for (int i = 0; i < 4000; ++i) {
        double x = i * 0.137, y = i * 0.071, z = i * 0.053;
        const double v3 = perlin3(a, x, y, z);
        lo = std::min(lo, v3), hi = std::max(hi, v3);
        diff += std::abs(v3 - perlin3(c, x, y, z));
    }
    EXPECT_GE(lo, -1.05);
    EXPECT_LE(hi, 1.05);
    EXPECT_LT(lo, -0.4);  // it does vary
    EXPECT_GT(hi, 0.4);
    EXPECT_GT(diff, 100.0);
    // Continuity: a small step changes the value a little.
    EXPECT_NEAR(perlin3(a, 0.5, 0.5, 0.5), perlin3(a, 0.5001, 0.5, 0.5), 1e-3);
}

TEST(IndicationTextures, EveryPointLiesOnTheModel) {
    TriangleMesh m = block_on_lawn();
    auto lines = indication_textures(m, load_texture_library(kLib), house_style(0.6f, 3));
    ASSERT_GT(lines.size(), 50u);
    for (const auto& l : lines) {
        EXPECT_EQ(l.kind, "texture");
        for (const auto& p : l.points) ASSERT_TRUE(on_mesh(m, p)) << p.x << " " << p.y << " " << p.z;
    }
    std::map<std::string, int> per_material;
    for (const auto& l : lines) per_material[l.material]++;
    EXPECT_GT(per_material["walls"], 0);
    EXPECT_GT(per_material["ground"], 0);
    EXPECT_GT(per_material["roof"], 0);
}

TEST(IndicationTextures, CountFallsAsTheThresholdRises) {
    TriangleMesh m = block_on_lawn();
    TextureLibrary lib = load_texture_library(kLib);
    std::size_t prev = ~std::size_t(0);
    for (float th : {0.2f, 0.6f, 0.9f, 1.2f}) {
        std::size_t n = point_count(indication_textures(m, lib, house_style(th, 3)));
        EXPECT_LT(n, prev) << "threshold " << th;
        prev = n;
    }
    EXPECT_EQ(indication_textures(m, lib, house_style(1.7f, 3)).size(), 0u);  // above 1 + edge_weight
}

TEST(IndicationTextures, DenserAlongFeatureEdges) {
    TriangleMesh m = block_on_lawn();
    TextureOptions o = house_style(0.7f, 5);
    auto lines = indication_textures(m, load_texture_library(kLib), o);
    // Lawn stroke length per m^2 within 1.5 m of the block's foot (feature edges) against the
    // ring 1.5..2.5 m from it, which is also > 1.5 m from the lawn's outer boundary at 6 m.
    double near_len = 0, far_len = 0;
    for (const auto& l : lines) {
        if (l.material != "ground") continue;
        for (std::size_t i = 1; i < l.points.size(); ++i) {
            glm::vec3 p = 0.5f * (l.points[i] + l.points[i - 1]);
            float d = std::max(std::abs(p.x), std::abs(p.y)) - 2.0f;  // distance to the foot square
            float seg = glm::length(l.points[i] - l.points[i - 1]);
            if (d < 1.5f) near_len += seg;
            if (d > 1.5f && d < 2.5f) far_len += seg;
        }
    }
    const double near_area = 7.0 * 7.0 - 4.0 * 4.0, far_area = 9.0 * 9.0 - 7.0 * 7.0;
    EXPECT_GT(near_len / near_area, 1.5 * far_len / far_area) << near_len << " " << far_len;
    EXPECT_GT(near_len, 0.0);
}

TEST(IndicationTextures, DeterministicPerSeedAndSketchinessMatters) {
    TriangleMesh m = block_on_lawn();
    TextureLibrary lib = load_texture_library(kLib);
    auto a = indication_textures(m, lib, house_style(0.6f, 11));
    auto b = indication_textures(m, lib, house_style(0.6f, 11));
    auto c = indication_textures(m, lib, house_style(0.6f, 12));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i].points, b[i].points);
    bool differs = a.size() != c.size();
    for (std::size_t i = 0; !differs && i < a.size(); ++i) differs = a[i].points != c[i].points;
    EXPECT_TRUE(differs);
    // Confidence 1: bricks are exactly the library strokes (horizontal bed joints stay level).
    TextureOptions exact = house_style(0.0f, 11);
    exact.materials["walls"].confidence = 1.0f;
    exact.materials.erase("ground");
    exact.materials.erase("roof");
    auto walls = indication_textures(m, lib, exact);
    ASSERT_FALSE(walls.empty());
    TextureOptions sketchy = exact;
    sketchy.materials["walls"].confidence = 0.0f;
    auto loose = indication_textures(m, lib, sketchy);
    ASSERT_FALSE(loose.empty());
    EXPECT_NE(walls[0].points, loose[0].points);
}
