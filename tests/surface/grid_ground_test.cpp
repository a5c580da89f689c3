// grid_ground_height against point location on the full-resolution mesh (TerrainLocator over
// mesh_from_terrain): same triangle, same linear height, on an affine grid (volcano.asc) and on
// the curvilinear grid of a geographic DEM projected to UTM (jacksboro.tif).
#include <random>

#include <gtest/gtest.h>

#include "input/dem_reader.hpp"
#include "surface/grid_ground.hpp"
#include "surface/surface_mesh.hpp"
#include "surface/terrain_locator.hpp"

namespace penink {
namespace {

// Heights of the mesh's flat triangles under (x, y), as the walk must find them.
bool mesh_height(const SurfaceMesh& m, const TerrainLocator& loc, double x, double y, double& z) {
    SurfaceHit hit;
    if (!loc.locate(x, y, hit)) return false;
    const glm::uvec3 v = m.tri[hit.triangle];
    z = double(hit.bary.x) * m.pos[v.x].z + double(hit.bary.y) * m.pos[v.y].z + double(hit.bary.z) * m.pos[v.z].z;
    return true;
}

// Random plan points over the DEM's box and a margin beyond it: inside and outside agree, and
// heights agree to 1e-3 m (the locator's barycentrics are floats: ~1e-7 of the ~1000 m relief).
void compare(const Terrain& t, int samples) {
    const SurfaceMesh mesh = mesh_from_terrain(t);
    const TerrainLocator loc(mesh);
    glm::dvec3 lo, hi;
    ASSERT_TRUE(terrain_bounds(t, lo, hi));
    const double mx = 0.05 * (hi.x - lo.x), my = 0.05 * (hi.y - lo.y);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> ux(lo.x - mx, hi.x + mx), uy(lo.y - my, hi.y + my);
    int inside = 0, outside = 0;
    for (int i = 0; i < samples; ++i) {
        const double x = ux(rng), y = uy(rng);
        double za = 0, zb = 0;
        const bool a = grid_ground_height(t, x, y, za), b = mesh_height(mesh, loc, x, y, zb);
        ASSERT_EQ(a, b) << "x " << x << " y " << y;
        if (a) {
            EXPECT_NEAR(za, zb, 1e-3) << "x " << x << " y " << y;
            ++inside;
        } else {
            ++outside;
        }
    }
    EXPECT_GT(inside, samples / 2);
    EXPECT_GT(outside, 10);
}

TEST(GridGround, AffineGridMatchesTheMesh) {
    compare(read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc"), 5000);
}

TEST(GridGround, CurvilinearGridMatchesTheMesh) {
    compare(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 5000);
}

TEST(GridGround, NodesGiveTheirOwnHeight) {
    const Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    for (int r = 1; r + 1 < t.rows; r += 7)
        for (int c = 1; c + 1 < t.cols; c += 5) {
            double z = 0;
            const glm::vec3 p = t.pos[t.index(c, r)];
            ASSERT_TRUE(grid_ground_height(t, p.x, p.y, z));
            EXPECT_NEAR(z, p.z, 1e-4);
        }
}

}  // namespace
}  // namespace penink
