// The taper of a stroke's width towards its ends (the pen's lift): one formula for the writers
// (export/styled_drawing) and for the ink the hachures count (lines/hachures).
#pragma once

namespace penink {

// Width factor of a tapered stroke at arc length `at` of `length` px: taper_min at the ends,
// 1 from `taper` px in (half the length when shorter), easing in between (1 - (1 - u)^2).
double taper_factor(double at, double length, double taper, double taper_min);

}  // namespace penink
