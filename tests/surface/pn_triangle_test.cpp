// PN triangles (Vlachos et al. 2001) against hand-computed control points, and the surface mesh's
// triangles and normals against values worked out by hand.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/synthetic_terrain.hpp"
#include "surface/pn_triangle.hpp"
#include "surface/surface_mesh.hpp"

using namespace penink;

namespace {

void expect_vec(const glm::vec3& a, const glm::vec3& b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

std::uint32_t float_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// Random terrain-like PN triangles (a grid cell's half, heights and tilted unit normals) at random
// barycentric weights.
struct RandomPatches {
    explicit RandomPatches(unsigned seed) : rng(seed) {}
    void next(glm::vec3 p[3], glm::vec3 n[3], glm::vec3& bary) {
        const float dx = spacing(rng), dy = spacing(rng), x0 = 1000.0f * b(rng), y0 = 1000.0f * b(rng);
        p[0] = {x0, y0, h(rng)}, p[1] = {x0, y0 - dy, h(rng)}, p[2] = {x0 + dx, y0 - dy, h(rng)};
        for (int k = 0; k < 3; ++k) n[k] = glm::normalize(glm::vec3(tilt(rng), tilt(rng), 1.0f));
        float u = b(rng), w = b(rng);
        if (u + w > 1.0f) u = 1.0f - u, w = 1.0f - w;
        bary = glm::vec3(1.0f - u - w, u, w);
    }
    std::mt19937 rng;
    std::uniform_real_distribution<float> h{-50.0f, 900.0f}, tilt{-0.8f, 0.8f}, spacing{1.0f, 40.0f}, b{0.0f, 1.0f};
};

}  // namespace

// Flat triangle with normals tilted outward. By hand, for p0=(0,0,0), p1=(3,0,0), p2=(0,3,0),
// n0=(0,0,1), n1=(0.6,0,0.8), n2=(0,0,1):
//   w01 = (p1-p0).n0 = 0 -> b210 = (2p0+p1)/3 = (1,0,0)
//   w10 = (p0-p1).n1 = -1.8 -> b120 = (2p1+p0 + 1.8 n1)/3 = (6+1.08, 0, 1.44)/3 = (2.36, 0, 0.48)
//   w12 = (p2-p1).n1 = -1.8 -> b021 = (2p1+p2 + 1.8 n1)/3 = (7.08, 3, 1.44)/3 = (2.36, 1, 0.48)
//   b012 = (2p2+p1)/3 = (1,2,0), b102 = (2p2+p0)/3 = (0,2,0), b201 = (2p0+p2)/3 = (0,1,0)
//   E = mean of the six = (6.72, 6, 0.96)/6 = (1.12, 1, 0.16); V = (1,1,0)
//   b111 = E + (E - V)/2 = (1.18, 1, 0.24)
TEST(PnTriangle, ControlPointsMatchHandComputation) {
    const glm::vec3 p0(0, 0, 0), p1(3, 0, 0), p2(0, 3, 0), n0(0, 0, 1), n1(0.6f, 0, 0.8f), n2(0, 0, 1);
    const PnPatch q = pn_patch(p0, p1, p2, n0, n1, n2);
    expect_vec(q.b[0], p0), expect_vec(q.b[1], p1), expect_vec(q.b[2], p2);
    expect_vec(q.b[3], {1, 0, 0});
    expect_vec(q.b[4], {2.36f, 0, 0.48f});
    expect_vec(q.b[5], {2.36f, 1, 0.48f});
    expect_vec(q.b[6], {1, 2, 0});
    expect_vec(q.b[7], {0, 2, 0});
    expect_vec(q.b[8], {0, 1, 0});
    expect_vec(q.b[9], {1.18f, 1, 0.24f});
    // Corners interpolate the vertices and their normals.
    expect_vec(pn_position(q, {1, 0, 0}), p0), expect_vec(pn_position(q, {0, 1, 0}), p1);
    expect_vec(pn_normal(q, {0, 1, 0}), n1);
    // Centre: sum of b_ijk * 3!/(i!j!k!) / 27 = (b300+b030+b003)/27 + 3(sum of edge points)/27
    //        + 6 b111/27 = (3,3,0)/27 + 3(6.72,6,0.96)/27 + 6(1.18,1,0.24)/27.
    const glm::vec3 centre = (glm::vec3(3, 3, 0) + 3.0f * glm::vec3(6.72f, 6, 0.96f) + 6.0f * glm::vec3(1.18f, 1, 0.24f)) / 27.0f;
    expect_vec(pn_position(q, glm::vec3(1.0f / 3.0f)), centre, 1e-5f);
}

TEST(PnTriangle, PlanarPatchStaysPlanar) {
    const glm::vec3 n(0, 0, 1);
    const PnPatch q = pn_patch({0, 0, 5}, {10, 0, 5}, {0, 10, 5}, n, n, n);
    for (float u = 0; u <= 1.0f; u += 0.25f)
        for (float v = 0; u + v <= 1.0f; v += 0.25f) {
            const glm::vec3 p = pn_position(q, {1 - u - v, u, v});
            EXPECT_NEAR(p.z, 5.0f, 1e-5f);
            EXPECT_NEAR(p.x, 10 * u, 1e-4f);  // on a plane PN reproduces the linear map
            expect_vec(pn_normal(q, {1 - u - v, u, v}), n);
        }
}

TEST(PnTriangle, SphereVerticesBulgeTowardTheSphere) {
    // Vertices on the unit sphere with exact normals: the patch centre moves outward, closer to r=1.
    const glm::vec3 a = glm::normalize(glm::vec3(1, 0, 0.2f)), b = glm::normalize(glm::vec3(0, 1, 0.2f)),
                    c = glm::normalize(glm::vec3(0, 0, 1));
    const PnPatch q = pn_patch(a, b, c, a, b, c);
    const float flat = glm::length((a + b + c) / 3.0f), curved = glm::length(pn_position(q, glm::vec3(1.0f / 3.0f)));
    // For this octant-sized patch (vertices ~80 degrees apart) the flat centre is at r = 0.70 and
    // the cubic PN centre at r = 0.84: it halves the distance to the sphere (it cannot reach it).
    EXPECT_LT(flat, 0.71f);
    EXPECT_GT(curved, 0.84f);
    EXPECT_LT(1.0f - curved, 0.6f * (1.0f - flat));
}

// The height-only evaluation gives pn_position's z and pn_normal of the full patch to the bit
// (the drainage drape stores them; its golden files are byte for byte): random terrain-like
// triangles (a grid cell's half, heights and tilted unit normals) at random barycentric weights.
TEST(PnTriangle, HeightNormalIsThePatchsZAndNormalBitForBit) {
    RandomPatches patches(7);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 p[3], nv[3], bary;
        patches.next(p, nv, bary);
        const PnPatch q = pn_patch(p[0], p[1], p[2], nv[0], nv[1], nv[2]);
        const glm::vec3 want_p = pn_position(q, bary), want_n = pn_normal(q, bary);
        glm::vec3 n;
        const float z = pn_height_normal(p[0], p[1], p[2], nv[0], nv[1], nv[2], bary, n);
        ASSERT_EQ(float_bits(z), float_bits(want_p.z)) << i;
        ASSERT_EQ(float_bits(n.x), float_bits(want_n.x)) << i;
        ASSERT_EQ(float_bits(n.y), float_bits(want_n.y)) << i;
        ASSERT_EQ(float_bits(n.z), float_bits(want_n.z)) << i;
        ++checked;
    }
    EXPECT_EQ(checked, 20000);
}

// Four patches at once give each patch's pn_height_normal to the bit, lanes mixed with the
// degenerate cases that take the other side of its choices (a zero-length edge: no reflection;
// opposite vertex normals: a zero mid-edge normal, the fallback taken).
TEST(PnTriangle, FourLanesAreTheHeightNormalBitForBit) {
    RandomPatches patches(11);
    for (int i = 0; i < 5000; ++i) {
        glm::vec3 p[4][3], n[4][3], t[4];
        for (int lane = 0; lane < 4; ++lane) {
            patches.next(p[lane], n[lane], t[lane]);
            const int odd = (i + lane) % 16;
            if (odd == 1) p[lane][1] = p[lane][0];  // a zero-length edge
            if (odd == 2)  // opposite vertex normals: nothing to reflect, the fallback's normalised sum
                n[lane][1] = glm::vec3(1, 0, 0), n[lane][0] = glm::vec3(-1, 0, 0);
        }
        float z[4];
        glm::vec3 normal[4];
        pn_height_normal4(p, n, t, z, normal);
        for (int lane = 0; lane < 4; ++lane) {
            glm::vec3 want_n;
            const float want_z = pn_height_normal(p[lane][0], p[lane][1], p[lane][2], n[lane][0], n[lane][1], n[lane][2],
                                                  t[lane], want_n);
            ASSERT_EQ(float_bits(z[lane]), float_bits(want_z)) << i << " " << lane;
            for (int k = 0; k < 3; ++k) ASSERT_EQ(float_bits(normal[lane][k]), float_bits(want_n[k])) << i << " " << lane;
        }
    }
}

TEST(SurfaceMesh, TwoCounterClockwiseTrianglesPerCellAndNormals) {
    // 3x2 nodes of z = x (a 45-degree slope rising east), 10 m spacing.
    const Terrain t = terrain_from_function(3, 2, 10.0, [](double x, double) { return x; });
    const SurfaceMesh m = mesh_from_terrain(t);
    ASSERT_EQ(m.tri.size(), 4u);
    EXPECT_EQ(m.tri[0], glm::uvec3(0, 3, 4));  // NW, SW, SE
    EXPECT_EQ(m.tri[1], glm::uvec3(0, 4, 1));  // NW, SE, NE
    const glm::vec3 expected = glm::normalize(glm::vec3(-1, 0, 1));
    for (const glm::vec3& n : m.face_normal) expect_vec(n, expected, 1e-6f);
    for (const glm::vec3& n : m.normal) expect_vec(n, expected, 1e-6f);
}

TEST(SurfaceMesh, VertexNormalIsNormalisedSumOfIncidentFaceNormals) {
    // A roof ridge along y: z = 10 - |x|. The ridge vertex sees faces of both sides.
    const Terrain t = terrain_from_function(3, 2, 10.0, [](double x, double) { return 10.0 - std::abs(x); });
    const SurfaceMesh m = mesh_from_terrain(t);
    // Node 1 (top middle) lies in 1 west-side face (0,4,1) and 2 east-side faces (1,4,5), (1,5,2).
    const glm::vec3 west = glm::normalize(glm::vec3(-1, 0, 1)), east = glm::normalize(glm::vec3(1, 0, 1));
    expect_vec(m.normal[1], glm::normalize(west + 2.0f * east), 1e-6f);
    // Nodata: a missing node drops the triangles touching it.
    Terrain holes = t;
    holes.valid[5] = 0;
    EXPECT_EQ(mesh_from_terrain(holes).tri.size(), 2u);
}
