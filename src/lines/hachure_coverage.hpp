// Ink coverage against a target tone on a coarse grid of image cells: the hachures' feedback
// (Winkenbach & Salesin 1994, "Computer-generated pen-and-ink illustration": strokes are laid
// until the tone each region asks for is reached). Image pixels, cells of `cell` px.
//
// Per cell: the terrain pixels it holds (from the frame's depth image, or the whole cell where a
// target sample fell and no depth image is given), the mean target tone of the samples that fell
// in it, and the ink laid in it (each stroke segment's length x its pen width, at its midpoint's
// cell). The gain at a pixel is (box-summed target ink) / (box-summed ink) over the 3 x 3 cells
// around the cell, target ink = mean tone x terrain pixels, interpolated bilinearly between cell
// centres (the mean tone weighs each sample by its area): > 1 where the drawing is lighter than its target, < 1 where it is darker. A cell's ink
// counts at most its terrain pixels (overlapping lines do not darken paper twice); only cells with
// a target sample count, and a cell with none around it has gain 1.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "core/pixel_mask.hpp"

namespace penink {

class InkCoverage {
public:
    InkCoverage(int width, int height, float cell);

    // The terrain pixels of each cell: the finite depths of `depth` (same size as the image); an
    // empty image leaves every cell that gets a target sample counted whole.
    void set_terrain(const DepthImage& depth);
    // A sample of the target tone at an image point of the drawn terrain, weighed by the image
    // area it stands for (the mean tone of a cell is an area mean).
    void add_target(glm::vec2 px, double tone, double weight = 1.0);
    // Ink of a segment a-b drawn `width` px wide, counted in the cells it crosses (split at 1 px);
    // `fixed`: ink that clear_ink keeps (lines drawn before).
    void add_ink(glm::vec2 a, glm::vec2 b, double width, bool fixed = false);
    void clear_ink();

    // The gain at image point px (see above), in [0, max_gain].
    double gain(glm::vec2 px, double max_gain) const;
    // Share of the target's ink the drawing lays over the cells with a target (diagnostics, tests).
    double ink_share() const;

    // Per-cell gains (box-smoothed ratios); call after the ink and targets are in.
    void update(double max_gain);

private:
    int index(glm::vec2 px) const;
    // Cell i's target ink (its mean sampled tone over its terrain pixels; call where it has a
    // sample) and the ink laid in it, at most its terrain pixels.
    double wanted(std::size_t i) const { return tone_sum_[i] / tone_n_[i] * terrain_[i]; }
    double laid(std::size_t i) const { return std::min(ink_[i] + fixed_[i], terrain_[i]); }
    int cols_ = 0, rows_ = 0;
    float cell_ = 8.0f;
    bool counted_terrain_ = false;
    std::vector<double> terrain_, tone_sum_, tone_n_, ink_, fixed_, gain_;
};

}  // namespace penink
