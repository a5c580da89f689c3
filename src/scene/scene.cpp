// A scene's names and value checks (scene.hpp); the scene file is read by scene_file.cpp.
#include "scene/scene.hpp"

#include <cstdio>
#include <utility>

#include "core/error.hpp"
#include "drainage/drainage_build.hpp"
#include "scene/hachure_lines.hpp"

namespace penink {

namespace {

// "NAME must be between LO and HI UNIT (got V)" unless lo <= v <= hi.
void check_range(const std::string& file, const std::string& name, double v, double lo, double hi,
                 const std::string& unit = "") {
    if (v >= lo && v <= hi) return;
    throw Error("scene", file, name + " must be between " + message_number(lo) + " and " + message_number(hi) + unit +
                                   " (got " + message_number(v) + ")");
}

void check_range(const std::string& file, const std::string& name, const std::optional<double>& v, double lo,
                 double hi, const std::string& unit) {
    if (v) check_range(file, name, *v, lo, hi, unit);
}

}  // namespace

std::optional<SilhouetteMethod> silhouette_method_named(const std::string& name) {
    for (SilhouetteMethod m : {SilhouetteMethod::toward_away, SilhouetteMethod::adjacency, SilhouetteMethod::edge_walk,
                               SilhouetteMethod::object_space})
        if (name == silhouette_method_name(m)) return m;
    return std::nullopt;
}

const char* silhouette_method_name(SilhouetteMethod method) {
    switch (method) {
        case SilhouetteMethod::adjacency: return "adjacency";
        case SilhouetteMethod::edge_walk: return "edge-walk";
        case SilhouetteMethod::object_space: return "object-space";
        case SilhouetteMethod::toward_away: break;
    }
    return "toward-away";
}

void validate_scene(const Scene& s) {
    const std::string& f = s.source.file.empty() ? s.source.dem : s.source.file;
    if (s.view.camera.width <= 0 || s.view.camera.height <= 0)
        throw Error("scene", f, "image size must be positive (got " + std::to_string(s.view.camera.width) +
                                    "x" + std::to_string(s.view.camera.height) + ")");
    if (s.view.camera.width > max_image_side || s.view.camera.height > max_image_side)
        throw Error("scene", f, "image size is too large (at most " + std::to_string(max_image_side) + " pixels a side)");
    if (!(s.view.camera.fov > 0.0 && s.view.camera.fov < 179.0))
        throw Error("scene", f, "camera fov must be between 0 and 179 degrees");
    if (!(s.terrain.vertical_exaggeration > 0.0 && s.terrain.vertical_exaggeration <= max_vertical_exaggeration))
        throw Error("scene", f, "vertical exaggeration must be > 0 and at most 1000 (got " +
                                    message_number(s.terrain.vertical_exaggeration) + ")");
    check_range(f, "[camera] altitude", s.view.camera.altitude, -90.0, 90.0, " degrees");
    check_range(f, "[camera] azimuth", s.view.camera.azimuth, -360.0, 360.0, " degrees");
    check_range(f, "[camera] elevation", s.view.camera.elevation, -1e7, 1e7, " metres");
    check_range(f, "[terrain] sea_level", s.terrain.sea_level, -1e7, 1e7, " metres");
    check_range(f, "[light] altitude", s.view.light.altitude, 0.0, 90.0, " degrees");  // a sun: above the horizon
    check_range(f, "[light] azimuth", s.view.light.azimuth, -360.0, 360.0, " degrees");
    for (const auto& [name, p] : {std::pair<const char*, const CreaseParams*>{"creases", &s.lines.creases}, {"ridges", &s.lines.ridges}}) {
        const std::string t = std::string("[") + name + "] ";
        check_range(f, t + "slope_weight", p->slope_weight, 0.0, 1000.0);
        check_range(f, t + "illumination_weight", p->illumination_weight, 0.0, 1000.0);
        check_range(f, t + "flow_weight", p->flow_weight, 0.0, 1000.0);
        check_range(f, t + "min_score", p->min_score, -1000.0, 1000.0);
        check_range(f, t + "distance_attenuation", p->distance_attenuation, 0.0, 1000.0);
        check_range(f, t + "spacing_px", p->spacing_px, 0.0, 1000.0);
    }
    validate_hachures(s.lines.hachures, f);
    check_range(f, "[silhouettes] min_gap", double(s.lines.silhouette_min_gap), 0.0, 1000.0);
    if (s.terrain.tess_max_level < 1 || s.terrain.tess_max_level > 64)
        throw Error("scene", f, "tessellation max_level must be between 1 and 64");
    if (!(s.terrain.surface_tolerance_px >= 0.0f && s.terrain.surface_tolerance_px <= 1000.0f))
        throw Error("scene", f, "[surface] tolerance_px must be between 0 and 1000");
    if (!(s.terrain.surface_min_radius_px >= 0.0f && s.terrain.surface_min_radius_px <= 1000.0f))
        throw Error("scene", f, "[surface] min_radius_px must be between 0 and 1000");
    if (!(s.terrain.tess_target_edge_px > 0.0f && s.terrain.tess_target_edge_px <= 1000.0f))
        throw Error("scene", f, "tessellation target_edge_px must be > 0 and at most 1000");
    if (!drainage_routing_named(s.terrain.drainage_routing))
        throw Error("scene", f, "[drainage] routing must be \"priority-flood\" or \"least-cost\" (got \"" +
                                    s.terrain.drainage_routing + "\")");
    const bool ortho = s.view.camera.projection == Projection::orthographic;
    if (!ortho && s.view.camera.position.has_value() != s.view.camera.elevation.has_value())
        throw Error("scene", f, "camera position and elevation go together (give both or neither)");
    const SceneCamera& c = s.view.camera;
    if (c.target && c.position && (c.azimuth || c.altitude))
        throw Error("scene", f, "camera azimuth and altitude follow from position and target: give one or the other");
    if (c.target && c.position && ortho)
        throw Error("scene", f, "an orthographic view is centred on its position or its target, not both");
    if (c.distance && !c.target) throw Error("scene", f, "camera distance goes with a target (the place looked at)");
    if (c.distance && c.position) throw Error("scene", f, "camera distance and position both place the camera: give one");
    check_range(f, "[camera] distance", c.distance, 1e-3, 1e8, " metres");
    if (s.view.map_scale != 0.0) {
        check_range(f, "[map] scale", s.view.map_scale, 1.0, 1e9);
        if (!ortho)
            throw Error("scene", f, "a map scale needs an orthographic view ([camera] projection = \"orthographic\", or --map)");
    }
}

std::optional<Projection> projection_named(const std::string& name) {
    for (Projection p : {Projection::perspective, Projection::orthographic})
        if (name == projection_name(p)) return p;
    return std::nullopt;
}

const char* projection_name(Projection projection) {
    return projection == Projection::orthographic ? "orthographic" : "perspective";
}

}  // namespace penink
