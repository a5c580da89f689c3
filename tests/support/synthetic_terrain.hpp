// Analytic terrains with closed-form answers for tests and benchmarks: a Terrain sampled from
// z = f(x, y) on a regular grid (local metres, row 0 north, origin (0, 0)), the usual shapes
// (Gaussian hill, hemisphere bump on a plane, step cliff, ridge, flat plain) and nodata holes.
// Their exact silhouettes are in support/synthetic_silhouettes.hpp (test-support library).
#pragma once
#include <functional>

#include "input/terrain.hpp"

namespace penink {

using HeightFunction = std::function<double(double x, double y)>;

// cols x rows nodes spaced `spacing` metres, centred on (0, 0); all nodes valid.
Terrain terrain_from_function(int cols, int rows, double spacing, const HeightFunction& f);

// height * exp(-(x^2 + y^2) / (2 sigma^2))
HeightFunction gaussian_hill(double height, double sigma);

enum class AnalyticShape {
    plain,          // z = 0
    gaussian_hill,  // z = height exp(-(x^2 + y^2) / (2 width^2))
    hemisphere,     // z = sqrt(width^2 - x^2 - y^2) inside the disc of radius width, else 0
    cliff,          // step: z = height where y <= 0 (south), 0 where y > 0; vertical at y = 0
    ridge,          // z = height exp(-x^2 / (2 width^2)): a crest along the y axis
};

struct AnalyticTerrain {
    AnalyticShape shape = AnalyticShape::gaussian_hill;
    double height = 250.0;       // metres (hemisphere: unused, its height is `width`)
    double width = 150.0;        // sigma of hill/ridge, radius of the hemisphere, metres
    double half_extent = 2000.0; // the grid covers [-half_extent, half_extent]^2
};

HeightFunction analytic_height(const AnalyticTerrain& shape);

// The shape sampled every `spacing` metres over its extent (a node on every multiple of spacing,
// so the cliff's top edge y = 0 is a grid row).
Terrain analytic_grid(const AnalyticTerrain& shape, double spacing);

// A sum of Gaussian hills (120-420 m, sigma 90-700 m, centred within 1.3 km of the origin) with
// fractal roughness: 9 octaves of ripples, wavelength 1024 m down to 4 m, amplitude 1.5 % of the
// wavelength (15 m to 6 cm), in turning directions: like a real DEM, detail at every scale.
double rough_hills(double x, double y);

// Marks the nodes within `radius` of (cx, cy) as nodata.
void cut_hole(Terrain& terrain, double cx, double cy, double radius);

}  // namespace penink
