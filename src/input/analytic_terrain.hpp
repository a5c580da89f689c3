// Analytic terrains with closed-form answers, for tests and the speed/accuracy chart: surfaces
// z = f(x, y) (local metres, x east, y north, origin (0, 0)) with their gradient, a Terrain grid
// sampled from them (row 0 north), and their exact silhouettes for a camera (core/camera.hpp).
// The silhouette is the visible part of the contour generator n(p) . (eye - p) = 0 (Mower, "Fast
// Image-Space Silhouette Extraction", sec. 2: the silhouette of a smooth surface), found
//  - in closed form where it exists (hemisphere: the tangent circle of the sphere; ridge: two lines
//    x = x* solving f'(x)(x - ex) + ez - f(x) = 0; cliff: its top edge y = 0, z = height, when the
//    step faces the eye on one side only, plus the hidden foot),
//  - by bisection to 1e-9 m along 7200 rays from the axis (Gaussian hill),
//  - for the other smooth shapes as the zero set of g(x, y) = -f_x (ex - x) - f_y (ey - y) + ez - f
//    on a grid of at most 4001^2 nodes (<= 2 m apart), each crossing refined by bisection along
//    its cell edge and the crossings chained cell to cell (marching squares).
// Visibility: a point is hidden where the surface lies above the grazing ray on both sides of it
// (the surface is concave along the ray: second difference of f along the ray > 0) or where the
// segment eye -> p, marched in 1 m steps against the exact height and stopping 0.5 % short of p,
// passes under the surface. Optionally only the parts where the ray beyond p meets the surface
// inside the extent (what a depth-image method sees against terrain). Output: image polylines in
// pixels (origin top-left, y down), the frame of lines/line_accuracy.hpp's ImagePolyline.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "input/terrain.hpp"

namespace penink {

using HeightFunction = std::function<double(double x, double y)>;

enum class AnalyticShape {
    plain,          // z = 0
    gaussian_hill,  // z = height exp(-(x^2 + y^2) / (2 width^2))
    hemisphere,     // z = sqrt(width^2 - x^2 - y^2) inside the disc of radius width, else 0
    cliff,          // step: z = height where y <= 0 (south), 0 where y > 0; vertical at y = 0
    ridge,          // z = height exp(-x^2 / (2 width^2)): a crest along the y axis
    two_hills,      // Gaussian hill (height, width) at the origin and one 1.6x as high, 1.5x as
                    // wide, at (0.8 width, 4 width): one behind the other seen from the south
    smooth_cliff,   // z = height (1 - tanh(y / width)) / 2: a steep smooth step, high side south,
                    // steepest slope height / (2 width) at y = 0
    saddle,         // two Gaussian peaks (height, width) at (+-1.5 width, 0): a col (saddle point)
                    // at the origin, 0.65 height high
};

struct AnalyticTerrain {
    AnalyticShape shape = AnalyticShape::gaussian_hill;
    double height = 250.0;       // metres (hemisphere: unused, its height is `width`)
    double width = 150.0;        // sigma of hill/ridge/peaks, radius of the hemisphere, cliff's
                                 // tanh scale, metres
    double half_extent = 2000.0; // the grid covers [-half_extent, half_extent]^2
};

HeightFunction analytic_height(const AnalyticTerrain& shape);
// (df/dx, df/dy) where f is smooth (the cliff: 0; the hemisphere: inside its disc, else 0).
glm::dvec2 analytic_gradient(const AnalyticTerrain& shape, double x, double y);

// cols x rows nodes spaced `spacing` metres, centred on (0, 0); all nodes valid.
Terrain terrain_from_function(int cols, int rows, double spacing, const HeightFunction& f);

// The shape sampled every `spacing` metres over its extent (a node on every multiple of spacing,
// so the cliff's top edge y = 0 is a grid row); elevation_min/max span 0 and every node's height.
Terrain analytic_grid(const AnalyticTerrain& shape, double spacing);

// Contour generator as world-space curves (ordered points, a few metres apart or closer).
std::vector<std::vector<glm::dvec3>> analytic_contour_generator(const AnalyticTerrain& shape, const glm::dvec3& eye);

// Visible, projected reference silhouettes; only_surface_behind keeps the parts with terrain
// behind them. Points farther than 5 px apart on screen start a new polyline.
std::vector<std::vector<glm::vec2>> analytic_silhouettes(const AnalyticTerrain& shape, const Camera& cam,
                                                         bool only_surface_behind = true);

// The named test and benchmark terrains, each with its grid spacing and a grazing view from the
// south (horizontal fov 40 deg, depth range fitted to the extent):
//   "hill":         Gaussian hill 250 m, sigma 150 m, 4 km square, 25 m grid, eye (0, -1300, 450) m
//                   looking 10 deg down;
//   "two-hills":    two_hills 250 m, sigma 150 m, 6 km square, 25 m grid, eye (0, -1300, 700) m,
//                   14 deg down: the near hill hides the far one's foot;
//   "smooth-cliff": smooth_cliff 100 m, width 15 m, 2 km square, 5 m grid, eye (-150, -600, 260) m,
//                   azimuth 15 deg, 15 deg down: the cliff's brink across the image;
//   "saddle":       saddle 250 m, sigma 150 m, 6 km square, 25 m grid, eye (0, -1300, 520) m,
//                   12 deg down.
struct AnalyticCase {
    std::string name;
    AnalyticTerrain shape;
    double spacing = 25.0;  // grid, metres
    Camera camera;
};
std::optional<AnalyticCase> analytic_case(const std::string& name, int width, int height);
// The names analytic_case knows, comma-separated.
std::string analytic_case_names();

}  // namespace penink
