// Analytic terrains with closed-form answers for tests and benchmarks: a Terrain sampled from
// z = f(x, y) on a regular grid (local metres, row 0 north, origin (0, 0)), and the usual
// shapes (Gaussian hill, tilted plane, step/cliff, ridge, closed depression).
#pragma once
#include <functional>

#include "input/terrain.hpp"

namespace penink {

using HeightFunction = std::function<double(double x, double y)>;

// cols x rows nodes spaced `spacing` metres, centred on (0, 0); all nodes valid.
Terrain terrain_from_function(int cols, int rows, double spacing, const HeightFunction& f);

// height * exp(-(x^2 + y^2) / (2 sigma^2))
HeightFunction gaussian_hill(double height, double sigma);

}  // namespace penink
