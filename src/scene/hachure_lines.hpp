// The hachures layer of a terrain frame (lines/hachures.hpp): the scene's [hachures] table read
// and checked, and one frame's hachures traced on the modelled nodes after its creases, ridges
// and silhouettes (which the hachures yield to), against the frame's nearest-surface depth.
#pragma once
#include <string>
#include <vector>

#include <toml.hpp>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"
#include "lines/hachures.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

// Reads [hachures] (enabled, tone, blend, contrast, gamma, min_slope_deg, spacing_min_px,
// spacing_max_px, width_px, d_test, yield_px, max_turn_deg, aerial, min_length_px) into p;
// throws Error("scene", file, "[hachures] KEY: ...") on a wrong type or name.
// The keys [hachures] takes.
const std::vector<std::string>& hachure_keys();
void read_hachures(const toml::value& root, HachureParams& p, const std::string& file);
// One-line range errors ("[hachures] KEY must be between LO and HI (got V)").
void validate_hachures(const HachureParams& p, const std::string& file);

// The frame's hachures into drawing's hachures layer (nothing when disabled).
// params.width_px is the pen width the spacing is computed for (0: default_hachure_width_px).
void add_hachures(const FrameTerrain& terrain, const Camera& camera, const DepthImage& toward,
                  const glm::dvec3& light, const HachureParams& params, Drawing& drawing);

}  // namespace penink
