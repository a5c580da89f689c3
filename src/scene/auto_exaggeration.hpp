// The vertical exaggeration that makes a DEM's relief read as landforms whatever its extent
// ([terrain] vertical_exaggeration = "auto", the default for DEMs): the exaggerated relief is
// about a twentieth of the DEM's longer plan side,
//     e = t * extent / relief,  t = 1/20,
// rounded to the nearest of 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8 times a power of ten (log scale)
// and held to [1, 25]: never flattened below the truth, never more than 25 (a plain with a few
// metres of relief stays a plain). relief = highest minus lowest valid elevation (metres,
// unexaggerated; above the sea level when one is set), extent = longer side of the DEM's plan box
// (metres). Examples: Maunga Whau (870 m across, 101 m relief) 1; the Jacksboro DEM (32 km,
// 840 m) 2; a coastal DEM 300 km across with 2 km of relief 8.
#pragma once

#include <string>

namespace penink {

constexpr double auto_exaggeration_relief_share = 1.0 / 20.0;
constexpr double max_auto_exaggeration = 25.0;

double auto_vertical_exaggeration(double relief_m, double extent_m);

// "relief 101 m over 870 m: vertical exaggeration 1 (auto)" for --verbose.
std::string describe_auto_exaggeration(double relief_m, double extent_m, double exaggeration);

}  // namespace penink
