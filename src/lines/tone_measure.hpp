// How well a drawing's ink draws a target tone (the hachures' measure; it shares no code with
// lines/hachures.hpp). Ink I = 1 - luminance of the rendered image (Rec. 709 weights on the 8-bit
// values / 255). Target T = 1 - max(0, n . l) per pixel: the pixel's centre unprojected with the
// frame's depth image (eye distance, core/camera.hpp's depth) to a world point, located on the
// DEM's grid (the affine basis of nodes (0, 0), (1, 0), (0, 1), then Newton steps on the cells'
// bilinear maps for a curvilinear grid) and n the normal of the bilinear patch of its cell's four
// nodes (finite differences), l the unit vector towards the
// light; a point whose bilinear height is at or below the grid's sea level is water and has no
// target (a map does not tone the sea: it is drawn flat, without hachures). Both are blurred with a Gaussian of sigma px normalised over the drawn terrain (pixels
// with a finite depth and a target), and compared on the terrain pixels farther than 2 sigma from
// its outline: Pearson r, SSIM of the two blurred fields as one window (absolute values; C1 =
// 0.01^2, C2 = 0.03^2; Wang, Bovik, Sheikh & Simoncelli 2004), mean I and mean T. Ink per unit
// of drawn terrain (the unblurred mean of I over terrain pixels) in the near, middle and far thirds
// of the terrain's depth range.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

// A DEM grid as drawn, for the target: cols x rows nodes, row-major, row 0 north (world metres,
// z exaggerated), valid flags.
struct ToneGrid {
    int cols = 0, rows = 0;
    const glm::vec3* pos = nullptr;
    const std::uint8_t* valid = nullptr;
    double z_scale = 1.0;  // drawn z = stored z * z_scale
    // A sea level (drawn z): ground at or below it is drawn as flat water, which a map leaves
    // untoned (no hachures on water), so the target leaves it out; -inf: no sea.
    double sea_z = -std::numeric_limits<double>::infinity();
};

// Row-major width x height floats; NaN where there is no value.
struct ToneImage {
    int width = 0, height = 0;
    std::vector<float> v;
};

// 1 - luminance of 8-bit RGB pixels (3 bytes each).
ToneImage ink_from_rgb(int width, int height, const std::vector<std::uint8_t>& rgb);

// T at each pixel with a finite depth that lands on a valid cell above the sea, else NaN.
ToneImage target_tone(const ToneGrid& grid, const Camera& camera, const DepthImage& depth, const glm::dvec3& light);

struct ToneScore {
    double sigma = 0.0;
    std::size_t pixels = 0;  // compared pixels
    double r = 0.0, ssim = 0.0, mean_ink = 0.0, mean_target = 0.0;
};
// Blurred comparison at sigma px (see above).
ToneScore tone_score(const ToneImage& ink, const ToneImage& target, double sigma);

// Mean ink per terrain pixel in the near, middle and far thirds of [min, max] depth over the
// pixels where target is defined.
std::array<double, 3> ink_by_depth_thirds(const ToneImage& ink, const ToneImage& target, const DepthImage& depth);

}  // namespace penink
