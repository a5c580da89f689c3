// CPU PN tessellation: OpenGL's triangle tessellation pattern (triangle counts per level, full
// CCW cover of the unit triangle with no overlap), the GPU's level rule, and welding: the
// tessellated surface of a grid is a closed sheet whose only boundary is the grid's border,
// with uniform and with mixed (view-dependent) levels.
#include <map>

#include <gtest/gtest.h>

#include "core/camera.hpp"
#include "support/synthetic_terrain.hpp"
#include "surface/pn_tessellation.hpp"

using namespace penink;

namespace {

PnLevels levels(int o0, int o1, int o2, int inner) {
    PnLevels lv;
    lv.outer = {o0, o1, o2};
    lv.inner = inner;
    return lv;
}

// Signed area sum in (b1, b2) coordinates and the smallest single signed area.
std::pair<double, double> areas(const BaryTriangulation& bt) {
    double sum = 0.0, min_area = 1.0;
    for (const glm::uvec3& t : bt.tri) {
        const glm::vec3 a = bt.bary[t.x], b = bt.bary[t.y], c = bt.bary[t.z];
        const double ar = 0.5 * ((b.y - a.y) * (c.z - a.z) - (b.z - a.z) * (c.y - a.y));
        sum += ar, min_area = std::min(min_area, ar);
    }
    return {sum, min_area};
}

// Number of triangles using each undirected edge.
std::map<std::pair<unsigned, unsigned>, int> edge_use(const std::vector<glm::uvec3>& tri) {
    std::map<std::pair<unsigned, unsigned>, int> use;
    for (const glm::uvec3& t : tri)
        for (int k = 0; k < 3; ++k) {
            const unsigned a = t[k], b = t[(k + 1) % 3];
            ++use[{std::min(a, b), std::max(a, b)}];
        }
    return use;
}

}  // namespace

TEST(PnTessellation, UniformLevelsFollowTheGlRingPattern) {
    // Rings of n, n-2, ... segments per side; strips of 3 (s + s - 2) triangles, a centre
    // triangle when n is odd: 1, 6, 13, 24, 37 for n = 1..5.
    const int expected[] = {1, 6, 13, 24, 37};
    for (int n = 1; n <= 5; ++n) {
        const BaryTriangulation bt = tessellate_unit_triangle(levels(n, n, n, n));
        EXPECT_EQ(int(bt.tri.size()), expected[n - 1]) << "level " << n;
        const auto [sum, min_area] = areas(bt);
        EXPECT_NEAR(sum, 0.5, 1e-6);
        EXPECT_GT(min_area, 0.0);
    }
}

TEST(PnTessellation, MixedOuterLevelsCoverTheTriangleOnce) {
    const BaryTriangulation bt = tessellate_unit_triangle(levels(1, 3, 5, 5));
    const auto [sum, min_area] = areas(bt);
    EXPECT_NEAR(sum, 0.5, 1e-6);
    EXPECT_GT(min_area, 0.0);
    int on_side[3] = {0, 0, 0};
    for (int e : bt.edge)
        if (e >= 0 && e < 3) ++on_side[e];
    EXPECT_EQ(on_side[0], 0);  // level 1: corners only
    EXPECT_EQ(on_side[1], 2);
    EXPECT_EQ(on_side[2], 4);
    // Every edge is used once (border) or twice (inside); border edges = 1 + 3 + 5.
    int border = 0;
    for (const auto& [e, n] : edge_use(bt.tri)) {
        EXPECT_LE(n, 2);
        border += n == 1;
    }
    EXPECT_EQ(border, 9);
    EXPECT_TRUE(tessellate_unit_triangle([] { PnLevels l; l.culled = true; return l; }()).tri.empty());
}

TEST(PnTessellation, FlatGridWeldsIntoOneSheet) {
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(4, 4, 10.0, [](double, double) { return 5.0; }));
    const PnTessellation t = tessellate_pn_surface_uniform(mesh, 3);
    EXPECT_EQ(t.tri.size(), mesh.tri.size() * 13);
    int border = 0;
    for (const auto& [e, n] : edge_use(t.tri)) {
        EXPECT_LE(n, 2);
        border += n == 1;
    }
    EXPECT_EQ(border, 4 * 3 * 3);  // 4 sides x 3 cells x 3 segments
    for (std::size_t i = 0; i < t.pos.size(); ++i) {
        EXPECT_FLOAT_EQ(t.pos[i].z, 5.0f);
        EXPECT_NEAR(t.normal[i].z, 1.0f, 1e-6f);
    }
}

TEST(PnTessellation, ViewDependentLevelsStayCrackFree) {
    const SurfaceMesh mesh = mesh_from_terrain(terrain_from_function(21, 21, 20.0, gaussian_hill(80.0, 60.0)));
    Camera cam;
    cam.eye = {0.0, -260.0, 120.0};
    cam.azimuth = 0.0, cam.altitude = -20.0, cam.fov = 60.0, cam.width = 400, cam.height = 300;
    fit_depth_range(cam, {-200, -200, 0}, {200, 200, 80});
    const glm::dmat4 vp = view_projection(cam);
    const PnTessellation t = tessellate_pn_surface(mesh, vp, {400.0f, 300.0f}, 8.0f, 16);
    std::map<int, int> level_count;
    for (const glm::uvec3& tr : mesh.tri) {
        const PnLevels lv = pn_patch_levels(pn_patch(mesh.pos[tr.x], mesh.pos[tr.y], mesh.pos[tr.z],
                                                     mesh.normal[tr.x], mesh.normal[tr.y], mesh.normal[tr.z]),
                                            glm::mat4(vp), {400.0f, 300.0f}, 8.0f, 16);
        ++level_count[lv.culled ? 0 : lv.inner];
    }
    EXPECT_GE(level_count.size(), 3u) << "near patches finer than far ones";
    EXPECT_GT(level_count[0], 0) << "patches behind the camera are culled";
    // Edges used once: grid border edges plus the borders of culled regions; never more than 2.
    int over = 0;
    for (const auto& [e, n] : edge_use(t.tri)) over += n > 2;
    EXPECT_EQ(over, 0);
    // Without culling (uniform) the border is exactly the grid's.
    int border = 0;
    for (const auto& [e, n] : edge_use(tessellate_pn_surface_uniform(mesh, 2).tri)) border += n == 1;
    EXPECT_EQ(border, 4 * 20 * 2);
}
