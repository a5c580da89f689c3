// Terrain level of detail (surface/terrain_lod.hpp): triangle budget against the image on 2049^2
// and 2000^2 analytic DEMs (2 m spacing), crack-freeness (no T-junction, interior edges shared by
// exactly two triangles, plan area = the DEM's), projected vertical error <= the tolerance at
// every visible DEM node, flat terrain collapsing, nodata holes keeping the full-resolution
// triangles, errors independent of the vertical exaggeration, full-resolution normals, and the
// nesting of errors and radii that makes all of this hold.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <set>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/camera.hpp"
#include "surface/surface_mesh.hpp"
#include "surface/terrain_lod.hpp"
#include "support/synthetic_terrain.hpp"

using namespace penink;

namespace {

constexpr double kSpacing = 2.0;
constexpr double kPi = 3.14159265358979323846;

// cols x rows nodes spaced 2 m, centred on (0, 0), row 0 north; z = f(x, y) * exaggeration.
Terrain grid_terrain(int cols, int rows, const std::function<double(double, double)>& f, double exaggeration = 1.0) {
    Terrain t;
    t.cols = cols, t.rows = rows;
    t.vertical_exaggeration = exaggeration;
    t.xy_unit = 1.0;
    t.pos.resize(t.size());
    t.valid.assign(t.size(), 1);
    double zmin = 1e300, zmax = -1e300;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double x = (c - (cols - 1) * 0.5) * kSpacing, y = ((rows - 1) * 0.5 - r) * kSpacing;
            const double z = f(x, y);
            zmin = std::min(zmin, z), zmax = std::max(zmax, z);
            t.pos[t.index(c, r)] = glm::vec3(float(x), float(y), float(z * exaggeration));
        }
    t.elevation_min = zmin, t.elevation_max = zmax;
    return t;
}

// The 2049 x 2049 test DEM, made once.
const Terrain& big_hills() {
    static const Terrain t = grid_terrain(2049, 2049, rough_hills);
    return t;
}

// The conventions' default view: from the south-west (looking north-east), 30 degrees down,
// the whole DEM in the frame (so nothing is culled).
Camera framing_camera(const Terrain& t, int width = 1000, int height = 750) {
    glm::dvec3 lo, hi;
    terrain_bounds(t, lo, hi);
    return frame_box(lo, hi, {.azimuth = 45.0, .altitude = -30.0, .fov = 40.0, .width = width, .height = height});
}

// A low camera inside the DEM looking across it (grazing, much of the DEM culled).
Camera grazing_camera(const Terrain& t) {
    Camera cam;
    const glm::vec3 p = t.pos[t.index(t.cols / 4, 3 * t.rows / 4)];
    cam.eye = glm::dvec3(p.x, p.y, p.z + 60.0);
    cam.azimuth = 50.0, cam.altitude = -8.0, cam.fov = 50.0;
    cam.width = 1000, cam.height = 750;
    cam.near_plane = 1.0, cam.far_plane = 20000.0;
    return cam;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Selected {
    SurfaceMesh mesh;
    LodSelection stats;
    std::vector<std::uint32_t> nodes;  // DEM node of each vertex
    double select_ms = 0.0;
};

Selected select(const TerrainLod& lod, const Terrain& t, const Camera& cam, float tol = 1.0f) {
    Selected s;
    const auto t0 = std::chrono::steady_clock::now();
    s.mesh = select_lod_mesh(lod, t, cam, tol, &s.stats, &s.nodes);
    s.select_ms = ms_since(t0);
    return s;
}

struct GridPoint {
    long c, r;
};
GridPoint grid_of(const Terrain& t, std::uint32_t node) { return {long(node % t.cols), long(node / t.cols)}; }

// Twice the signed plan area in grid units (column east, row south): negative = counter-clockwise
// seen from above.
long grid_cross2(GridPoint a, GridPoint b, GridPoint c) { return (b.c - a.c) * (c.r - a.r) - (b.r - a.r) * (c.c - a.c); }

struct CrackReport {
    std::size_t t_junctions = 0, interior_edges_not_two = 0, boundary_edges = 0, non_ccw = 0;
    double area_cells = 0.0;  // plan area in cells (grid units)
};

// No T-junction: no vertex of the mesh lies strictly inside an edge (grid lattice points along
// every edge). Edges whose midpoint is strictly inside the DEM are counted by use.
CrackReport crack_report(const Terrain& t, const Selected& s) {
    CrackReport rep;
    std::vector<std::uint8_t> used(t.size(), 0);
    for (const std::uint32_t n : s.nodes) used[n] = 1;
    std::vector<std::uint64_t> edges;
    edges.reserve(s.mesh.tri.size() * 3);
    for (const glm::uvec3& tri : s.mesh.tri) {
        const GridPoint g[3] = {grid_of(t, s.nodes[tri.x]), grid_of(t, s.nodes[tri.y]), grid_of(t, s.nodes[tri.z])};
        const long cr = grid_cross2(g[0], g[1], g[2]);
        if (cr >= 0) ++rep.non_ccw;
        rep.area_cells += std::abs(double(cr)) * 0.5;
        for (int k = 0; k < 3; ++k) {
            const GridPoint p = g[k], q = g[(k + 1) % 3];
            const long dc = q.c - p.c, dr = q.r - p.r, len = std::gcd(std::abs(dc), std::abs(dr));
            for (long i = 1; i < len; ++i)
                if (used[t.index(int(p.c + dc / len * i), int(p.r + dr / len * i))]) ++rep.t_junctions;
            const std::uint32_t u = s.nodes[tri[k]], v = s.nodes[tri[(k + 1) % 3]];
            edges.push_back(std::uint64_t(std::min(u, v)) << 32 | std::max(u, v));
        }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        const GridPoint a = grid_of(t, std::uint32_t(edges[i] >> 32)), b = grid_of(t, std::uint32_t(edges[i]));
        const long mc2 = a.c + b.c, mr2 = a.r + b.r;  // twice the midpoint
        const bool interior = mc2 > 0 && mc2 < 2L * (t.cols - 1) && mr2 > 0 && mr2 < 2L * (t.rows - 1);
        if (interior && j - i != 2) ++rep.interior_edges_not_two;
        if (j - i == 1) ++rep.boundary_edges;
        i = j;
    }
    return rep;
}

struct ErrorReport {
    std::size_t checked = 0, uncovered = 0;
    double max_px = 0.0;        // the brief's metric: |dz| * focal / distance
    double max_true_px = 0.0;   // the two points' actual image distance (project_to_pixel)
};

// At every DEM node seen in the frame: the selected mesh's height over the node (grid-space
// barycentrics = world barycentrics on this affine grid) against the node's own.
ErrorReport error_report(const Terrain& t, const Selected& s, const Camera& cam) {
    std::vector<float> zmesh(t.size(), std::numeric_limits<float>::quiet_NaN());
    for (const glm::uvec3& tri : s.mesh.tri) {
        const GridPoint g[3] = {grid_of(t, s.nodes[tri.x]), grid_of(t, s.nodes[tri.y]), grid_of(t, s.nodes[tri.z])};
        const double z[3] = {s.mesh.pos[tri.x].z, s.mesh.pos[tri.y].z, s.mesh.pos[tri.z].z};
        const double area = double(grid_cross2(g[0], g[1], g[2]));
        const long c0 = std::min({g[0].c, g[1].c, g[2].c}), c1 = std::max({g[0].c, g[1].c, g[2].c});
        const long r0 = std::min({g[0].r, g[1].r, g[2].r}), r1 = std::max({g[0].r, g[1].r, g[2].r});
        for (long r = r0; r <= r1; ++r)
            for (long c = c0; c <= c1; ++c) {
                const GridPoint p{c, r};
                const double w0 = grid_cross2(p, g[1], g[2]) / area, w1 = grid_cross2(g[0], p, g[2]) / area,
                             w2 = grid_cross2(g[0], g[1], p) / area;
                if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                zmesh[t.index(int(c), int(r))] = float(w0 * z[0] + w1 * z[1] + w2 * z[2]);
            }
    }
    const double aspect = double(cam.width) / cam.height;
    const double focal = cam.height / (2.0 * std::tan(cam.fov * kPi / 360.0) / aspect);
    ErrorReport rep;
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (!t.valid[i]) continue;
        const glm::dvec3 q(t.pos[i]);
        glm::dvec2 px;
        double depth;
        if (!project_to_pixel(cam, q, px, depth)) continue;
        if (px.x < 0 || px.y < 0 || px.x > cam.width || px.y > cam.height || depth < cam.near_plane) continue;
        ++rep.checked;
        if (std::isnan(zmesh[i])) {
            ++rep.uncovered;
            continue;
        }
        const glm::dvec3 m(q.x, q.y, zmesh[i]);
        rep.max_px = std::max(rep.max_px, std::abs(m.z - q.z) * focal / glm::length(q - cam.eye));
        glm::dvec2 pm;
        double dm;
        if (project_to_pixel(cam, m, pm, dm)) rep.max_true_px = std::max(rep.max_true_px, glm::length(pm - px));
    }
    return rep;
}

// Dependants of a node (its four children in the diamond DAG), as build_terrain_lod defines them.
template <class F> void each_parent_child(int levels, F&& f) {
    const int n = 1 << levels;
    for (int s = 4; s <= n; s *= 2) {
        const int half = s / 2, q = s / 4;
        for (int r = 0; r <= n; r += half)
            for (int c = (r % s == 0) ? half : 0; c <= n; c += s)
                for (const int dr : {-q, q})
                    for (const int dc : {-q, q})
                        if (c + dc >= 0 && c + dc <= n && r + dr >= 0 && r + dr <= n) f(c, r, c + dc, r + dr);
        for (int r = half; r < n; r += s)
            for (int c = half; c < n; c += s) {
                f(c, r, c - half, r), f(c, r, c + half, r), f(c, r, c, r - half), f(c, r, c, r + half);
            }
    }
    if (n >= 2) {  // s = 2 centres (odd, odd): children the s = 2 edge nodes
        for (int r = 1; r < n; r += 2)
            for (int c = 1; c < n; c += 2) f(c, r, c - 1, r), f(c, r, c + 1, r), f(c, r, c, r - 1), f(c, r, c, r + 1);
    }
}

}  // namespace

// The budget: <= 2 W H triangles for a 1000 x 750 frame of a 4.2 M-node DEM (8.4 M full-res
// triangles), with timings printed.
TEST(TerrainLod, TriangleBudgetOn2049Grid) {
    const Terrain& t = big_hills();
    auto t0 = std::chrono::steady_clock::now();
    const TerrainLod lod = build_terrain_lod(t);
    const double build_ms = ms_since(t0);
    EXPECT_EQ(lod.levels, 11);
    EXPECT_EQ(lod.error.size(), std::size_t(2049) * 2049);
    const Camera cam = framing_camera(t);
    const Selected s = select(lod, t, cam);
    const std::size_t full = std::size_t(2) * 2048 * 2048;
    std::printf("2049x2049: build %.1f ms, select %.1f ms, %zu triangles (%.3f per pixel, full res %zu), %zu vertices, "
                "%zu active nodes\n",
                build_ms, s.select_ms, s.stats.triangles, s.stats.triangles / 750000.0, full, s.stats.vertices,
                s.stats.active_nodes);
    EXPECT_EQ(s.stats.triangles, s.mesh.tri.size());
    EXPECT_EQ(s.stats.vertices, s.mesh.pos.size());
    EXPECT_LE(s.stats.triangles, std::size_t(2) * 1000 * 750);
    EXPECT_LT(s.stats.triangles, full / 8);
    EXPECT_GT(s.stats.triangles, std::size_t(1000));  // it does refine the hills
    // A coarser tolerance needs fewer triangles (errors are smooth: roughly 1/tolerance).
    const Selected coarse = select(lod, t, cam, 4.0f);
    EXPECT_LT(coarse.stats.triangles, s.stats.triangles / 2);
    std::printf("2049x2049 tolerance 4 px: %zu triangles, select %.1f ms\n", coarse.stats.triangles, coarse.select_ms);
}

TEST(TerrainLod, TriangleBudgetOnNonPowerGrid) {
    const Terrain t = grid_terrain(2000, 2000, rough_hills);
    auto t0 = std::chrono::steady_clock::now();
    const TerrainLod lod = build_terrain_lod(t);
    const double build_ms = ms_since(t0);
    EXPECT_EQ(lod.levels, 11);  // padded to 2049
    const Selected s = select(lod, t, framing_camera(t));
    std::printf("2000x2000: build %.1f ms, select %.1f ms, %zu triangles, %zu vertices\n", build_ms, s.select_ms,
                s.stats.triangles, s.stats.vertices);
    EXPECT_LE(s.stats.triangles, std::size_t(2) * 1000 * 750);
    EXPECT_LT(s.stats.triangles, std::size_t(2) * 1999 * 1999 / 8);
    // Exactly the DEM's cells (nothing in the padding), crack-free.
    const CrackReport rep = crack_report(t, s);
    EXPECT_EQ(rep.t_junctions, 0u);
    EXPECT_EQ(rep.interior_edges_not_two, 0u);
    EXPECT_EQ(rep.non_ccw, 0u);
    EXPECT_EQ(rep.area_cells, 1999.0 * 1999.0);
    for (const std::uint32_t n : s.nodes) ASSERT_LT(n, t.size());
}

// With everything in view (no culling), every edge with its midpoint inside the DEM is shared by
// exactly two triangles, no vertex lies inside another triangle's edge, all triangles are
// counter-clockwise from above and they tile the DEM exactly (plan area in whole cells, exact).
TEST(TerrainLod, CrackFreeWithoutCulling) {
    const Terrain& t = big_hills();
    const TerrainLod lod = build_terrain_lod(t);
    for (const float tol : {1.0f, 0.25f, 3.0f}) {
        const Selected s = select(lod, t, framing_camera(t), tol);
        const CrackReport rep = crack_report(t, s);
        EXPECT_EQ(rep.t_junctions, 0u) << tol;
        EXPECT_EQ(rep.interior_edges_not_two, 0u) << tol;
        EXPECT_EQ(rep.non_ccw, 0u) << tol;
        EXPECT_EQ(rep.area_cells, 2048.0 * 2048.0) << tol;
        // Boundary edges: the DEM outline only (4 sides, at most one edge per boundary cell).
        EXPECT_LE(rep.boundary_edges, std::size_t(4) * 2048) << tol;
        // Face normals are the selected triangles' own.
        for (std::size_t i = 0; i < s.mesh.tri.size(); i += 97) {
            const glm::uvec3 tri = s.mesh.tri[i];
            const glm::vec3 n = glm::normalize(glm::cross(s.mesh.pos[tri.y] - s.mesh.pos[tri.x], s.mesh.pos[tri.z] - s.mesh.pos[tri.x]));
            EXPECT_NEAR(glm::dot(n, s.mesh.face_normal[i]), 1.0f, 1e-5f);
            EXPECT_GT(n.z, 0.0f);
        }
    }
}

// View-dependent thresholds with culling: a low camera inside the DEM. No T-junction anywhere;
// edges used once inside the DEM are only where a neighbour was culled, i.e. near the frustum.
TEST(TerrainLod, NoTJunctionsWithGrazingViewAndCulling) {
    const Terrain& t = big_hills();
    const TerrainLod lod = build_terrain_lod(t);
    const Camera cam = grazing_camera(t);
    const Selected s = select(lod, t, cam);
    std::printf("grazing 2049x2049: select %.1f ms, %zu triangles, %zu vertices\n", s.select_ms, s.stats.triangles,
                s.stats.vertices);
    EXPECT_LE(s.stats.triangles, std::size_t(2) * 1000 * 750);
    const CrackReport rep = crack_report(t, s);
    EXPECT_EQ(rep.t_junctions, 0u);
    EXPECT_EQ(rep.non_ccw, 0u);
    EXPECT_GT(rep.area_cells, 0.0);
    EXPECT_LT(rep.area_cells, 2048.0 * 2048.0);  // culled part of the DEM
    // Every visible node is covered and within the tolerance.
    const ErrorReport err = error_report(t, s, cam);
    std::printf("grazing: %zu nodes in view, max error %.3f px (true image distance %.3f px)\n", err.checked,
                err.max_px, err.max_true_px);
    EXPECT_GT(err.checked, std::size_t(100000));
    EXPECT_EQ(err.uncovered, 0u);
    EXPECT_LE(err.max_px, 1.0);
    EXPECT_LE(err.max_true_px, 1.0);
}

// Tolerance 1 px: at every DEM node in the frame, the vertical gap between the selected mesh and
// the full-resolution surface, projected at the node's distance, is <= 1 px. The selection uses
// a lower bound on that distance and an off-axis factor >= 1, and errors bound the gap at the
// nodes rigorously, so the inequality holds with no slack needed beyond float rounding (the
// heights are floats of a few hundred metres: ~3e-5 m, 1e-5 px at these distances).
TEST(TerrainLod, ProjectedErrorWithinTolerance) {
    const Terrain& t = big_hills();
    const TerrainLod lod = build_terrain_lod(t);
    const Camera cam = framing_camera(t);
    for (const float tol : {1.0f, 0.5f}) {
        const Selected s = select(lod, t, cam, tol);
        const ErrorReport rep = error_report(t, s, cam);
        std::printf("framing, tolerance %.2f px: %zu nodes checked, max error %.3f px (true %.3f px)\n", tol,
                    rep.checked, rep.max_px, rep.max_true_px);
        EXPECT_EQ(rep.checked, t.size());  // the whole DEM is in the frame
        EXPECT_EQ(rep.uncovered, 0u);
        EXPECT_LE(rep.max_px, tol + 1e-4);
        EXPECT_LE(rep.max_true_px, tol + 1e-4);
        EXPECT_GT(rep.max_px, 0.1 * tol);  // and it does simplify up to a good part of it
    }
}

// Flat: a 2^k + 1 DEM is 2 triangles (4 vertices); a tilted plane too (its errors are float
// rounding, ~1e-5 m, far below a pixel). A 2000 x 2000 DEM refines only next to the padding: the
// last column and row of cells at full resolution plus the triangles that reach them.
TEST(TerrainLod, FlatTerrainCollapses) {
    {
        const Terrain t = grid_terrain(1025, 1025, [](double, double) { return 120.0; });
        const TerrainLod lod = build_terrain_lod(t);
        const Selected s = select(lod, t, framing_camera(t));
        EXPECT_EQ(s.stats.triangles, 2u);
        EXPECT_EQ(s.stats.vertices, 4u);
        EXPECT_EQ(crack_report(t, s).area_cells, 1024.0 * 1024.0);
    }
    {
        const Terrain t = grid_terrain(1025, 1025, [](double x, double y) { return 300.0 + 0.2 * x - 0.1 * y; });
        const TerrainLod lod = build_terrain_lod(t);
        const Selected s = select(lod, t, framing_camera(t));
        EXPECT_EQ(s.stats.triangles, 2u);
    }
    {
        const Terrain t = grid_terrain(2000, 2000, [](double, double) { return 120.0; });
        const TerrainLod lod = build_terrain_lod(t);
        const Selected s = select(lod, t, framing_camera(t));
        std::printf("flat 2000x2000: %zu triangles\n", s.stats.triangles);
        const CrackReport rep = crack_report(t, s);
        EXPECT_EQ(rep.area_cells, 1999.0 * 1999.0);
        EXPECT_EQ(rep.t_junctions, 0u);
        EXPECT_EQ(rep.interior_edges_not_two, 0u);
        // The two full-resolution strips hold 2 * 2 * 1999 triangles; the transition to the
        // coarse interior adds about as many again.
        EXPECT_LE(s.stats.triangles, std::size_t(10) * 1999);
    }
}

// A nodata hole: no triangle uses an invalid node, every cell with an invalid corner keeps
// exactly the full-resolution triangles (those of its two whose nodes all hold data), and the
// mesh covers exactly the full-resolution mesh's area.
TEST(TerrainLod, NodataHoleKeepsFullResolutionOutline) {
    Terrain t = grid_terrain(1025, 1025, rough_hills);
    cut_hole(t, 150.0, -220.0, 180.0);
    cut_hole(t, -700.0, 500.0, 33.0);
    for (int c = 0; c < t.cols; ++c) t.valid[t.index(c, 700)] = c % 3 != 0;  // scattered nodata along a row
    const TerrainLod lod = build_terrain_lod(t);
    const Selected s = select(lod, t, framing_camera(t));
    std::printf("holes 1025x1025: %zu triangles\n", s.stats.triangles);
    for (const std::uint32_t n : s.nodes) ASSERT_TRUE(t.valid[n]);
    const SurfaceMesh full = mesh_from_terrain(t);
    double full_area = 0.0;
    std::set<std::array<std::uint32_t, 3>> next_to_nodata;  // full-res triangles in cells with an invalid corner
    auto cell_has_invalid = [&](int c, int r) {
        return !t.valid[t.index(c, r)] || !t.valid[t.index(c + 1, r)] || !t.valid[t.index(c, r + 1)] ||
               !t.valid[t.index(c + 1, r + 1)];
    };
    for (const glm::uvec3& tri : full.tri) {
        const GridPoint a = grid_of(t, tri.x), b = grid_of(t, tri.y), c = grid_of(t, tri.z);
        full_area += std::abs(double(grid_cross2(a, b, c))) * 0.5;
        const int cc = int(std::min({a.c, b.c, c.c})), cr = int(std::min({a.r, b.r, c.r}));
        if (cell_has_invalid(cc, cr)) next_to_nodata.insert({tri.x, tri.y, tri.z});
    }
    std::size_t found = 0;
    for (const glm::uvec3& tri : s.mesh.tri) {
        const std::array<std::uint32_t, 3> k = {s.nodes[tri.x], s.nodes[tri.y], s.nodes[tri.z]};
        const GridPoint a = grid_of(t, k[0]), b = grid_of(t, k[1]), c = grid_of(t, k[2]);
        const bool small = std::max({a.c, b.c, c.c}) - std::min({a.c, b.c, c.c}) == 1 &&
                           std::max({a.r, b.r, c.r}) - std::min({a.r, b.r, c.r}) == 1;
        if (!small) continue;
        const int cc = int(std::min({a.c, b.c, c.c})), cr = int(std::min({a.r, b.r, c.r}));
        if (!cell_has_invalid(cc, cr)) continue;
        // Same triangle (any rotation of the same counter-clockwise order).
        bool same = false;
        for (int rot = 0; rot < 3; ++rot)
            same |= next_to_nodata.count({k[rot], k[(rot + 1) % 3], k[(rot + 2) % 3]}) > 0;
        EXPECT_TRUE(same);
        found += same;
    }
    EXPECT_EQ(found, next_to_nodata.size());
    EXPECT_GT(found, 500u);
    const CrackReport rep = crack_report(t, s);
    EXPECT_EQ(rep.area_cells, full_area);
    EXPECT_EQ(rep.t_junctions, 0u);
    EXPECT_EQ(rep.non_ccw, 0u);
}

// Errors are stored unexaggerated: built with exaggeration 1 and 3 they agree to float rounding.
// h = float(float(z * e) / e) differs from z by <= 2 float roundings (2 * 2^-24 relative); an
// error is a signed sum of <= 2 * levels deltas of 3 heights each, plus as many float sums, so
// |error_1 - error_3| <= (2 * levels) * 8 * 2^-24 * max|z|; radii use plan positions only:
// identical. Selections differ (errors are scaled by e at selection).
TEST(TerrainLod, ErrorsDoNotDependOnExaggeration) {
    const Terrain t1 = grid_terrain(513, 513, rough_hills, 1.0), t3 = grid_terrain(513, 513, rough_hills, 3.0);
    const TerrainLod a = build_terrain_lod(t1), b = build_terrain_lod(t3);
    ASSERT_EQ(a.error.size(), b.error.size());
    const double bound = 2.0 * a.levels * 8.0 * std::ldexp(1.0, -24) * std::max(std::abs(t1.elevation_min), std::abs(t1.elevation_max));
    double worst = 0.0;
    for (std::size_t i = 0; i < a.error.size(); ++i) {
        ASSERT_EQ(std::isinf(a.error[i]), std::isinf(b.error[i]));
        if (!std::isinf(a.error[i])) worst = std::max(worst, double(std::abs(a.error[i] - b.error[i])));
    }
    EXPECT_EQ(a.lipschitz, b.lipschitz);
    EXPECT_LE(worst, bound);
    EXPECT_NEAR(a.z_max, b.z_max, 1e-4);
    const float emax = *std::max_element(a.error.begin(), a.error.end());
    EXPECT_GT(emax, 100.0f);  // the coarse levels do see the hills
    const Selected s1 = select(a, t1, framing_camera(t1)), s3 = select(b, t3, framing_camera(t3));
    EXPECT_GT(s3.stats.triangles, s1.stats.triangles);
}

// Vertex normals are the full-resolution mesh's (compute_normals on mesh_from_terrain), also
// next to nodata; same float operations in the same order, so 1e-5 is generous.
TEST(TerrainLod, NormalsAreFullResolutionNormals) {
    Terrain t = grid_terrain(600, 513, rough_hills);
    cut_hole(t, 100.0, 50.0, 40.0);
    const SurfaceMesh full = mesh_from_terrain(t);
    const TerrainLod lod = build_terrain_lod(t);
    for (const Camera& cam : {framing_camera(t), grazing_camera(t)}) {
        const Selected s = select(lod, t, cam);
        ASSERT_GT(s.mesh.pos.size(), 100u);
        ASSERT_EQ(s.mesh.normal.size(), s.mesh.pos.size());
        ASSERT_EQ(s.mesh.face_normal.size(), s.mesh.tri.size());
        for (std::size_t v = 0; v < s.nodes.size(); ++v) {
            EXPECT_EQ(s.mesh.pos[v], t.pos[s.nodes[v]]);
            EXPECT_LE(glm::length(s.mesh.normal[v] - full.normal[s.nodes[v]]), 1e-5f) << v;
        }
    }
}

// The nesting that makes activation monotone (hence crack-free meshes): every node's error and
// radius cover its four dependants'; error bounds the split vertex's own offset; +inf exactly
// on nodes with nodata or padding in their 3x3 neighbourhood or such a dependant.
TEST(TerrainLod, ErrorsAndRadiiAreNested) {
    Terrain t = grid_terrain(300, 257, rough_hills);
    cut_hole(t, 60.0, -40.0, 25.0);
    const TerrainLod lod = build_terrain_lod(t);
    EXPECT_EQ(lod.levels, 9);
    std::size_t pairs = 0;
    auto xy = [&](int c, int r) {
        const glm::vec3 p = t.pos[t.index(std::min(c, t.cols - 1), std::min(r, t.rows - 1))];
        return glm::vec2(p.x, p.y);
    };
    each_parent_child(lod.levels, [&](int pc, int pr, int cc, int cr) {
        ASSERT_GE(lod.error_at(pc, pr), lod.error_at(cc, cr)) << pc << "," << pr << " " << cc << "," << cr;
        ASSERT_GE(double(lod.radius(pc, pr)), double(lod.radius(cc, cr)) + glm::length(xy(pc, pr) - xy(cc, cr)));
        ++pairs;
    });
    EXPECT_GT(pairs, std::size_t(500000));
    // Interior node of the grid next to the hole and a padding node: forced; a far one: finite.
    EXPECT_TRUE(std::isinf(lod.error[lod.index(299, 10)]));
    EXPECT_TRUE(std::isinf(lod.error_at(400, 400)));
    EXPECT_TRUE(std::isfinite(lod.error[lod.index(11, 10)]));
    // The finest edge nodes' error is |h(m) - (h(a) + h(b)) / 2| for row-aligned hypotenuses.
    for (int r = 10; r < 200; r += 14)
        for (int c = 11; c < 100; c += 6) {
            const double h = t.pos[t.index(c, r)].z, ha = t.pos[t.index(c - 1, r)].z, hb = t.pos[t.index(c + 1, r)].z;
            EXPECT_NEAR(lod.error[lod.index(c, r)], std::abs(h - 0.5 * (ha + hb)), 1e-4);
        }
}

// A DEM rough at the cell scale (+-10 m white noise per 2 m node on a smooth base: slopes far
// beyond any real terrain's) is the error test's worst case: every cell deviates by more than a
// pixel even at the far side, so it refines towards full resolution (millions of triangles).
// The size floor caps that, keeps the mesh crack-free, and leaves smooth DEMs unchanged.
TEST(TerrainLod, SizeFloorCapsRoughTerrain) {
    Terrain t = grid_terrain(2049, 2049, [](double x, double y) { return 200.0 * std::sin(x / 600.0) * std::cos(y / 500.0); });
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c) {
            std::uint32_t h = std::uint32_t(c) * 2654435761u ^ std::uint32_t(r) * 2246822519u;
            h ^= h >> 15, h *= 2246822519u, h ^= h >> 13;
            t.pos[t.index(c, r)].z += float(20.0 * (h / 4294967296.0 - 0.5));
        }
    const TerrainLod lod = build_terrain_lod(t);
    const Camera cam = framing_camera(t);
    LodOptions o;
    LodSelection plain, floored;
    select_lod_mesh(lod, t, cam, o, &plain);
    o.min_radius_px = 2.0f;
    Selected s;
    s.mesh = select_lod_mesh(lod, t, cam, o, &floored, &s.nodes);
    std::printf("rough 2049x2049: %zu triangles by the error test alone, %zu with a 2 px size floor\n",
                plain.triangles, floored.triangles);
    EXPECT_GT(plain.triangles, std::size_t(2) * 1000 * 750);  // the worst case is real
    EXPECT_LE(floored.triangles, std::size_t(2) * 1000 * 750);
    const CrackReport rep = crack_report(t, s);
    EXPECT_EQ(rep.t_junctions, 0u);
    EXPECT_EQ(rep.interior_edges_not_two, 0u);
    EXPECT_EQ(rep.area_cells, 2048.0 * 2048.0);
    // On the smooth test DEM the floor changes nothing.
    const Terrain& smooth = big_hills();
    const TerrainLod slod = build_terrain_lod(smooth);
    LodSelection a, b;
    select_lod_mesh(slod, smooth, framing_camera(smooth), 1.0f, &a);
    select_lod_mesh(slod, smooth, framing_camera(smooth), o, &b);
    EXPECT_EQ(a.triangles, b.triangles);
}

// Tiny and thin grids: no cells, one cell, a strip; the mesh still tiles the DEM exactly.
TEST(TerrainLod, SmallGrids) {
    for (const auto& [cols, rows] : std::vector<std::pair<int, int>>{{1, 5}, {2, 2}, {3, 2}, {2, 3}, {5, 3}, {9, 9}, {17, 4}, {40, 2}}) {
        // Positive-definite quadratic: every split vertex is off its hypotenuse (delta = -d'Hd/8).
        const Terrain t = grid_terrain(cols, rows, [](double x, double y) { return 0.1 * (x * x + 2 * y * y + 0.5 * x * y); });
        const TerrainLod lod = build_terrain_lod(t);
        const Selected s = select(lod, t, framing_camera(t), 0.01f);
        if (cols < 2 || rows < 2) {
            EXPECT_TRUE(s.mesh.tri.empty());
            continue;
        }
        const CrackReport rep = crack_report(t, s);
        EXPECT_EQ(rep.area_cells, double(cols - 1) * (rows - 1)) << cols << "x" << rows;
        EXPECT_EQ(rep.t_junctions, 0u);
        EXPECT_EQ(rep.interior_edges_not_two, 0u);
        EXPECT_EQ(rep.non_ccw, 0u);
        // At a tolerance this fine everything is at full resolution: the full-res mesh's count.
        EXPECT_EQ(s.stats.triangles, std::size_t(2) * (cols - 1) * (rows - 1)) << cols << "x" << rows;
    }
}

// Water (GridNodes::sea_level): a plane tilted through the sea level simplifies to two triangles
// when dry, whose clamped corners (one under water raised to it) put the coarse plane half the
// range above the clamped DEM in the middle; with the water's bound the selection refines until
// the projected error against the clamped DEM is within the tolerance again, as on rough hills
// half drowned. The tolerance as in ProjectedErrorWithinTolerance (float rounding, 1e-4 px).
TEST(TerrainLod, WaterKeepsTheErrorBound) {
    const auto clamped = [](Terrain t, double sea) {
        for (glm::vec3& p : t.pos) p.z = std::max(p.z, float(sea));
        return t;
    };
    struct Case {
        const char* name;
        Terrain t;
        double sea;
    };
    for (const Case& k : {Case{"tilted plane", grid_terrain(513, 513, [](double x, double) { return 0.1 * x; }), 0.0},
                    Case{"rough hills", grid_terrain(513, 513, rough_hills), 200.0}}) {
        const TerrainLod lod = build_terrain_lod(k.t);
        const Camera cam = framing_camera(k.t);
        GridNodes wet = grid_nodes(k.t);
        wet.sea_level = k.sea;
        Selected s;
        s.mesh = select_lod_mesh(lod, wet, 1.0, cam, LodOptions{1.0f, 0.0f}, &s.stats, &s.nodes);
        const Terrain water = clamped(k.t, k.sea);
        const ErrorReport rep = error_report(water, s, cam);
        std::printf("%s with water: %zu triangles, max error %.3f px\n", k.name, s.stats.triangles, rep.max_px);
        EXPECT_EQ(rep.uncovered, 0u) << k.name;
        EXPECT_LE(rep.max_px, 1.0 + 1e-4) << k.name;
        // dry, the same view: the plane collapses, and its error against the clamped DEM is large
        Selected dry;
        dry.mesh = select_lod_mesh(lod, grid_nodes(k.t), 1.0, cam, LodOptions{1.0f, 0.0f}, &dry.stats, &dry.nodes);
        for (glm::vec3& p : dry.mesh.pos) p.z = std::max(p.z, float(k.sea));
        if (k.sea == 0.0) {
            EXPECT_GT(error_report(water, dry, cam).max_px, 10.0);
        }
    }
}

// A pyramid built on the clamped nodes (TerrainLod::sea_level) bounds the water as what it is, a
// flat plane: on an island rising 150 m out of a sea floor 600 m deep (bumps of 40 m everywhere)
// the DEM-wide water bound adds 150 m to every error and refines everything (measured 524 288
// triangles, full resolution); the clamped pyramid selects 2 204, within the same 1 px of the
// clamped DEM. A pyramid built for one sea level refuses nodes with another.
TEST(TerrainLod, PyramidBuiltWithTheSeaLevelSkipsTheSeaFloor) {
    const auto island = [](double x, double y) {
        const double r = std::hypot(x, y);  // metres from the grid's centre (1024 m across)
        return 750.0 * std::exp(-r * r / (2.0 * 120.0 * 120.0)) - 600.0 + 40.0 * std::sin(x / 23.0) * std::cos(y / 31.0);
    };
    Terrain t = grid_terrain(513, 513, island);
    const double sea = 0.0;
    GridNodes wet = grid_nodes(t);
    wet.sea_level = sea;
    const Camera cam = framing_camera(t);
    const TerrainLod dry_lod = build_terrain_lod(t);
    const TerrainLod wet_lod = build_terrain_lod(wet, 1.0);
    EXPECT_EQ(wet_lod.sea_level, sea);
    EXPECT_FLOAT_EQ(wet_lod.z_min, float(sea));
    Selected constant, built;
    constant.mesh = select_lod_mesh(dry_lod, wet, 1.0, cam, LodOptions{1.0f, 0.0f}, &constant.stats, &constant.nodes);
    built.mesh = select_lod_mesh(wet_lod, wet, 1.0, cam, LodOptions{1.0f, 0.0f}, &built.stats, &built.nodes);
    Terrain water = t;
    for (glm::vec3& p : water.pos) p.z = std::max(p.z, float(sea));
    const ErrorReport rep = error_report(water, built, cam);
    std::printf("island: %zu triangles with the DEM-wide water bound, %zu with the pyramid of the clamped nodes, "
                "max error %.3f px\n", constant.stats.triangles, built.stats.triangles, rep.max_px);
    EXPECT_EQ(rep.uncovered, 0u);
    EXPECT_LE(rep.max_px, 1.0 + 1e-4);
    EXPECT_LT(built.stats.triangles * 20, constant.stats.triangles);
    GridNodes other = wet;
    other.sea_level = 10.0;
    EXPECT_THROW(select_lod_mesh(wet_lod, other, 1.0, cam, LodOptions{}), std::invalid_argument);
    EXPECT_THROW(select_lod_mesh(wet_lod, grid_nodes(t), 1.0, cam, LodOptions{}), std::invalid_argument);
}
