// Direction measures of a layer's strokes in a plan view: how much of their length runs in the
// eight grid directions (the staircases of D8 flow paths, O'Callaghan & Mark 1984), and how far
// each segment turns from the fall line. What `penink render --verbose` prints per layer for a
// plan view and what bench/stroke_directions_bench.cpp reports for the stored creases and ridges.
// Frame: plan points in the Terrain's local metres (x east, y north). The grid directions are the
// directions of a D8 step in plan on the DEM cell under the segment's midpoint (its two edges and
// two diagonals: on a UTM-projected geographic grid neither square nor north-up; a resampled
// drainage grid's steps are parallel to them); off the DEM, the multiples of 45 degrees of the
// frame. The fall line comes
// from the DEM's own nodes, independently of how the lines were made: each node's gradient by
// central differences of its neighbours' positions (one-sided at the border and beside nodata),
// interpolated linearly over the DEM triangle under the point (dem_surface.hpp's DemDraper).
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "core/big_allocator.hpp"
#include "drainage/dem_surface.hpp"
#include "input/terrain.hpp"

namespace penink {

// The gradient dz/dx, dz/dy of a Terrain (positions as stored, z unexaggerated or not: the slope
// is measured on what is stored) at plan points. Keeps its own copy of the Terrain.
class FallLineField {
public:
    explicit FallLineField(Terrain t);
    struct Sample {
        glm::dvec2 gradient{0.0};  // dz/dx, dz/dy
        glm::dvec2 axes[4];        // unit plan directions of the cell's edges and diagonals
    };
    // False off the DEM's surface. `c`, `r`: a DEM cell near the point (the previous point's along
    // a line: on a grid without an affine formula the cell is found by walking from it), -1 when
    // none is known; set to the point's cell.
    bool sample(double x, double y, Sample& s, int& c, int& r) const;

private:
    Terrain terrain_;
    DemSurface surface_;
    std::vector<glm::vec2> grad_;  // per node
};

struct StrokeDirections {
    double length = 0.0;       // plan length of every segment, metres (or the caller's unit)
    double grid_length = 0.0;  // of which in segments within grid_tolerance of a grid direction
    // Angle of each segment to the fall-line axis at its midpoint (0-90 degrees), over segments
    // whose midpoint's slope exceeds min_slope: length-weighted median and 90th percentile.
    std::size_t sloped_segments = 0;
    double sloped_length = 0.0;
    double fall_median_deg = 0.0, fall_p90_deg = 0.0;
    double grid_share() const { return length > 0.0 ? grid_length / length : 0.0; }
};

// Segments shorter than 1e-9 of the unit are skipped. `lines`: plan polylines, local metres.
StrokeDirections stroke_directions(const std::vector<std::vector<glm::dvec2>>& lines, const FallLineField& field,
                                   double min_slope_deg = 5.0, double grid_tolerance_deg = 1.0);

}  // namespace penink
