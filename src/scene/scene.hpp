// A scene: what to draw and how, from a TOML scene file or a bare DEM path plus CLI options.
// Keys (all optional but the input): [terrain] dem, vertical_exaggeration (a number or "auto"),
// sea_level; [camera] projection, position, elevation, azimuth, altitude, target, distance, fov,
// width, height (a mesh scene's camera takes eye, target and up instead: scene/mesh_scene.hpp);
// [map] scale and the furniture keys (scene/map_furniture.hpp); [light] azimuth, altitude; [silhouettes]
// min_gap, separate_passes, method; [surface] tolerance_px, min_radius_px; [tessellation]
// target_edge_px, max_level, cull; [creases] and [ridges]
// slope_weight, illumination_weight, flow_weight, min_score, distance_attenuation, spacing_px,
// normalisation ("thirds", "paper" or "rank": core/crease_params.hpp), enabled; [hachures]
// (scene/hachure_lines.hpp); [style] name
// plus per-layer overrides; seed. Angles in degrees, distances in metres (conventions.md).
// A scene with [mesh] file draws a mesh instead (its keys: scene/mesh_scene.hpp). Any other key or
// table is an error naming the nearest known one; validate_scene holds the values to their ranges.
// A Scene is made of plain parts: where it comes from (SceneSource), how the terrain is modelled
// (TerrainSettings), what is seen (ViewSettings), which lines are traced (LineSettings), the pens
// (SceneStyle: the style resolved once at load) and a mesh's keys (MeshSettings). The file is read
// by scene_file.cpp, the only reader of its TOML.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/crease_params.hpp"
#include "lines/hachure_params.hpp"
#include "lines/map_furniture.hpp"
#include "export/style.hpp"
#include "render/terrain_renderer.hpp"

namespace penink {

// Limits validate_scene holds every scene to (and the command line's options).
constexpr int max_image_side = 16384;               // pixels
constexpr double max_vertical_exaggeration = 1000.0;

struct SceneCamera {
    // "perspective" (default) or "orthographic"; an orthographic view looks along azimuth and
    // altitude (altitude -90: a plan view, north up) at the DEM, or at `position` (its plan
    // point: the view's centre; elevation is not used).
    Projection projection = Projection::perspective;
    std::optional<std::string> position;  // UTM "E N 18N", "lon,lat" or "x y"; none = auto-frame
    std::optional<double> elevation;      // metres above the DEM's datum (scaled with exaggeration)
    std::optional<double> azimuth, altitude;  // none = conventions default (from the south-west)
    // A place to look at (same forms as position), on the ground. With a position the camera aims
    // at it (azimuth and altitude follow from the two); without one it stands `distance` metres
    // from it (none: half the DEM's plan diagonal) along azimuth and altitude, looking at it; in an
    // orthographic view it is the view's centre (as position is).
    std::optional<std::string> target;
    std::optional<double> distance;
    double fov = 40.0;
    int width = 1000, height = 750;
    // Orthographic: ground metres across the image (0: the DEM fills the image); set from
    // [map] scale and the page (scene/map_scale.hpp), not read from the scene file.
    double view_width = 0.0;
};

struct SceneLight {
    double azimuth = 315.0, altitude = 45.0;
};

// Where the scene comes from.
struct SceneSource {
    std::string file;  // the scene file ("" for a bare DEM or mesh path)
    std::string dem;   // DEM path (resolved relative to the scene file); a bare mesh path too
    std::string mesh;  // [mesh] file (resolved); "" for a terrain or a bare mesh path
};

// How the terrain is modelled: its heights, level of detail, tessellation and caches.
struct TerrainSettings {
    // [terrain] vertical_exaggeration: a number, or "auto" (the default for DEMs; resolved by
    // open_scene_terrain with auto_vertical_exaggeration, scene/auto_exaggeration.hpp).
    double vertical_exaggeration = 1.0;
    bool exaggeration_auto = true;
    bool exaggeration_was_auto = false;  // vertical_exaggeration was chosen automatically (metadata)
    // [terrain] sea_level: DEM elevation units, unexaggerated; nodes below it are drawn as a flat
    // water surface at it (GridNodes::sea_level) and its contour is the coastline layer. None: off.
    std::optional<double> sea_level;
    // [surface] level of detail (surface/terrain_lod.hpp): largest projected vertical error of the
    // frame's mesh against the DEM, pixels (0 = the full-resolution mesh), and the size floor: a
    // triangle whose bounding circle projects under min_radius_px pixels is not split further.
    float surface_tolerance_px = 1.0f;
    float surface_min_radius_px = 2.0f;
    int tess_max_level = 8;             // [tessellation] max_level
    float tess_target_edge_px = 6.0f;   // [tessellation] target_edge_px
    bool cull_patches = true;           // [tessellation] cull: leave out patches outside the view
    std::string drainage_routing = "priority-flood";  // [drainage] routing (drainage_build.hpp)
    std::string cache_dir;  // [cache] dir or --cache-dir (resolved); "": the default (drainage_cache_path)
    // --max-memory (0: the memory available): what the render's later builds (crease tiles) are
    // checked against, besides check_scene_memory's check before it starts.
    std::uint64_t max_memory = 0;
};

// What is seen and how it is lit: the camera, a plan view's scale and furniture, the sun.
struct ViewSettings {
    SceneCamera camera;
    // [map] scale: 25000 means 1:25 000 on the physical page (0: no scale); orthographic only.
    double map_scale = 0.0;
    // [map] furniture of a plan view (scene/map_furniture.hpp): neatline, scale bar, north arrow,
    // grid, title.
    MapFurnitureOptions furniture;
    SceneLight light;
};

// Which lines a terrain frame traces and how: creases, ridges, hachures, silhouettes.
struct LineSettings {
    CreaseParams creases = crease_defaults();
    CreaseParams ridges = ridge_defaults();
    // [hachures] (lines/hachures.hpp, scene/hachure_lines.hpp): slope lines spaced by tone; on for
    // DEMs. width_px 0 takes the style's hachures pen (hachure_pen, scene/hachure_lines.hpp).
    HachureParams hachures = hachure_defaults();
    float silhouette_min_gap = 0.0f;                                     // [silhouettes] min_gap
    SilhouetteMethod silhouette_method = SilhouetteMethod::toward_away;  // [silhouettes] method
    bool separate_passes = false;                                        // [silhouettes] separate_passes
};

// The pens: the style as named (or a style file), resolved once at load with the scene's [style]
// overrides applied, and the seed of the sketchy perturbation. The object-space sketch of creases
// and ridges (Potter et al., "NPR-Style 3D Line Textures", 4.3) and the hachures' pen are read
// from `resolved` by the terrain path.
struct SceneStyle {
    std::string name = "technical";    // [style] name or --style: a built-in name or a .toml path
    Style resolved = default_style();  // resolve_style(name) with the scene's [style] table over it
    std::uint64_t seed = 1;
};

// A mesh scene's keys (scene/mesh_scene.hpp): [mesh] up, subdivide; [camera] eye, target, up;
// [light] direction; [pels], [features], [textures]. Defaults for a bare mesh path and terrains.
struct MeshSettings {
    bool y_up = true;             // [mesh] up = "y" (default) or "z"
    int subdivide = 0;            // [mesh] subdivide: Loop subdivision iterations (0..4)
    std::optional<glm::dvec3> eye, target;  // [camera], mesh frame
    glm::dvec3 up{0, 1, 0};                 // [camera] up, mesh frame (default: the mesh's up)
    std::optional<glm::dvec3> light;        // [light] direction, mesh frame, towards the light
    bool pels = true;
    float pel_threshold = 0.1f;   // tau on the normalised |grad phi| (0..1)
    int smoothing = 0;            // Laplacian normal smoothing iterations
    // Xie et al., "Photic Extremum Lines" post-processing (docs/reproduction.md, PELs), both in
    // mean edge lengths of the mesh drawn (after subdivision), so they follow its resolution:
    float normal_filter = 0.0f;   // sigma of the Gaussian normal filter; 0 = none
    float line_strength = 0.0f;   // least integral of g along a PEL line; 0 = keep every line
    bool features = true;
    float crease_angle = 40.0f;   // degrees
    bool textures = true;
    float texture_threshold = 0.65f;
    float texture_confidence = 0.6f;       // 1 = exact strokes, 0 = very sketchy
    std::optional<float> texture_scale;    // cluster cell, mesh units (default: from the size)
    std::string texture_library;           // folder of *.txt clusters ("" = search: find_texture_library)
    std::map<std::string, std::string> materials;  // material name -> texture name
};

struct Scene {
    SceneSource source;
    TerrainSettings terrain;
    ViewSettings view;
    LineSettings lines;
    SceneStyle style;
    MeshSettings mesh;
};

// Silhouette methods by their scene and command-line names: "toward-away", "adjacency", "edge-walk",
// "object-space"; nullopt for any other name.
std::optional<SilhouetteMethod> silhouette_method_named(const std::string& name);
const char* silhouette_method_name(SilhouetteMethod method);

// Projections by their scene and command-line names: "perspective", "orthographic".
std::optional<Projection> projection_named(const std::string& name);
const char* projection_name(Projection projection);

// A path ending in .toml is a scene file; anything else is taken as a DEM (or a mesh by its
// extension). `style`, when not "", replaces the scene's [style] name (--style); the style is then
// resolved and the scene's [style] table applied over it. Throws penink::Error(stage "scene",
// file) with one line on a bad key or value, Error("style", ...) on a bad style.
Scene load_scene(const std::string& input, const std::string& style = "");

// Checks values that must hold whatever their source (CLI overrides included).
void validate_scene(const Scene& scene);

}  // namespace penink
