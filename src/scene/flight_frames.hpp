// The frames of a flight over a DEM (`penink batch`; Mower, "Concurrent Drainage Network
// Rendering", section 3: animation): one camera per flight-path record (scene/flight_path.hpp),
// each checked before the first frame is drawn, and the part of the DEM they need modelled once:
// the union of the DEM windows every frame sees (or the whole DEM). Cameras in the DEM's local
// world frame (metres, conventions.md), near/far fitted to the modelled terrain.
#pragma once
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/log.hpp"
#include "input/terrain.hpp"
#include "scene/flight_path.hpp"
#include "scene/scene.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

// The camera of one record over `dem`; errors name the CSV and line: "line N: cannot parse
// position ...", "line N: camera is inside the terrain (...)".
Camera flight_camera(const Scene& scene, const SceneTerrain& dem, const FlightRecord& record, const std::string& csv);

// The scene with one record's per-frame values (light; min_score sets the creases' threshold).
Scene frame_scene(const Scene& scene, const FlightRecord& record);

struct Flight {
    std::vector<FlightRecord> records;
    std::vector<Camera> cameras;  // one per record
    SceneTerrain dem;             // the whole DEM (terrain cache)
    FrameTerrain model;           // what the frames model
};

// Reads the flight path `csv` over the scene's DEM and checks every camera ("line N: the camera
// sees no part of the DEM"); models the union of their windows, or the whole DEM.
Flight plan_flight(Scene& scene, const std::string& csv, bool whole_dem, const Log& log);

}  // namespace penink
