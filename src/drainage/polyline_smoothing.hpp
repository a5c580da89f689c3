// Smooths plan polylines (the 45-degree staircase of D8 flow paths and divides) before the lines
// are draped back on the surface (draped_lines.hpp).
#pragma once
#include <vector>

#include <glm/vec2.hpp>

namespace penink {

// Gaussian smoothing of a polyline along its vertex index (standard deviation `sigma` vertices,
// kernel cut at 3 sigma), ends fixed: beyond each end the polyline continues as its point
// reflection through that end (so the end keeps its place and its tangent). `out` = `in`'s size.
void gaussian_smooth(const std::vector<glm::dvec2>& in, double sigma, std::vector<glm::dvec2>& out);

// The kernel of gaussian_smooth for one sigma, made once and applied to many polylines (the same
// floats as gaussian_smooth(in, sigma, out)).
class GaussianKernel {
public:
    explicit GaussianKernel(double sigma);
    void smooth(const std::vector<glm::dvec2>& in, std::vector<glm::dvec2>& out) const;
    // The offsets it weights on each side (ceil(3 sigma); 0 without smoothing): out[k] reads in[k
    // - radius] to in[k + radius], and the ends' reflections where those pass an end.
    int radius() const { return w_.empty() ? 0 : int(w_.size()) - 1; }

private:
    bool smooths_ = false;  // sigma > 0
    std::vector<double> w_;  // weights of offsets 0 .. radius
    double total_ = 0.0;
};

}  // namespace penink
