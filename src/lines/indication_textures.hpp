// Indication textures (Winkenbach & Salesin 1994, "Computer-Generated Pen-and-Ink Illustration",
// sec. 3.3 and 4): per-material line textures (bricks, stone, shingles, grass, hatching) built
// from a small library of hand-drawn stroke clusters (unit square, examples/textures/*.txt),
// placed on a grid in each planar face group's own 2D frame (world units: cell = style scale)
// where thresholded 3D Perlin noise plus a "near a feature edge" term exceeds a threshold (dense
// along feature edges, sparse elsewhere), jittered by a per-material sketchiness (confidence),
// clipped to the group's triangles (so cut at creases and boundaries), returned as world-space
// polylines of kind "texture". Deterministic for a seed (splitmix64 bits, no std distributions).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/triangle_mesh.hpp"
#include "lines/feature_edges.hpp"
#include "lines/photic_extremum_lines.hpp"

namespace penink {

// Classic Perlin gradient noise (Perlin 2002) with a permutation shuffled from a seed;
// values in about [-1, 1], 0 at integer lattice points.
struct PerlinNoise {
    std::array<std::uint8_t, 512> perm{};
};
PerlinNoise make_perlin(std::uint64_t seed);
double perlin3(const PerlinNoise& noise, double x, double y, double z);

using StrokeCluster = std::vector<std::vector<glm::vec2>>;  // strokes in the unit square
struct TextureLibrary {
    std::map<std::string, std::vector<StrokeCluster>> textures;  // name -> variants
};

// Reads every <name>.txt in dir (see examples/textures/bricks.txt for the format). Errors:
// penink::Error("textures", file, ...) "no texture library here", "odd number of coordinates",
// "coordinate outside the unit square", "bad number \"...\"", "no cluster".
TextureLibrary load_texture_library(const std::string& dir);

struct TextureStyle {
    std::string texture;      // name in the library ("" = no texture)
    float scale = 1.0f;       // cluster cell size, world units
    float confidence = 0.7f;  // 1 = exact strokes, 0 = very sketchy (jitter, overshoot)
};

struct TextureOptions {
    std::map<std::string, TextureStyle> materials;  // material name -> style
    float threshold = 0.65f;     // accept a cell where noise01 + edge term > threshold
    float noise_scale = 4.0f;    // Perlin feature size, world units
    float edge_band = 1.5f;      // world distance over which the feature-edge term falls to 0
    float edge_weight = 0.6f;    // value of the edge term on a feature edge
    float planar_angle = 1.0f;   // degrees: faces within it form one planar group
    glm::vec3 up{0, 0, 1};       // world up: texture rows are horizontal on walls
    FeatureOptions features;     // which edges bound groups and attract texture
    std::uint64_t seed = 1;
};

// Texture for a material name by keywords (brick/wall -> bricks, roof/shingle/tile -> shingles,
// stone/rock -> stone, grass/ground/lawn -> grass, hatch -> hatching), else "".
std::string default_texture_for_material(const std::string& material);

// Texture strokes for every face group whose material has a style with a known texture.
std::vector<ObjectPolyline> indication_textures(const TriangleMesh& mesh, const TextureLibrary& lib,
                                                const TextureOptions& options);

}  // namespace penink
