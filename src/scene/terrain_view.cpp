#include "scene/terrain_view.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "core/progress_bar.hpp"
#include "core/stopwatch.hpp"
#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"
#include "input/dem_file_identity.hpp"
#include "input/scene_position.hpp"
#include "input/terrain_window.hpp"
#include "core/georeference.hpp"
#include "export/page.hpp"
#include "scene/auto_exaggeration.hpp"
#include "scene/cache_build_estimate.hpp"
#include "scene/map_scale.hpp"
#include "scene/scene_memory.hpp"
#include "surface/grid_ground.hpp"

namespace penink {

namespace {

const std::string& scene_file(const Scene& s) { return s.source.file.empty() ? s.source.dem : s.source.file; }

// The camera of a scene over a DEM's nodes (drawn) with bounds lo, hi.
// A scene place (position or target) on the drawn ground: its plan point and the surface's height
// there (the middle of the relief off the DEM).
glm::dvec3 ground_point(const Scene& scene, const std::string& place, const Terrain& meta, const GridNodes& nodes,
                        const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec2 xy = parse_scene_position(place, meta, scene_file(scene));
    double ground = 0.5 * (lo.z + hi.z);
    grid_ground_height(nodes, xy.x, xy.y, ground);
    return {xy, ground};
}

Camera place_camera(const Scene& scene, const Terrain& meta, const GridNodes& nodes, const glm::dvec3& lo,
                    const glm::dvec3& hi) {
    const SceneCamera& sc = scene.view.camera;
    double az = sc.azimuth.value_or(default_view_azimuth);
    double alt = sc.altitude.value_or(default_view_altitude);
    if (sc.projection == Projection::orthographic) {
        Camera cam = frame_points_orthographic(frame_samples(nodes), {.azimuth = az, .altitude = alt, .width = sc.width,
                                                                         .height = sc.height, .view_width = sc.view_width,
                                                                         .fill = 0.95});
        if (const auto& centre = sc.position ? sc.position : sc.target) {  // the view centred on its plan point
            const glm::dvec3 d = direction_from_angles(az, alt);
            const glm::dvec3 to_target = ground_point(scene, *centre, meta, nodes, lo, hi) - cam.eye;
            cam.eye += to_target - d * glm::dot(to_target, d);  // sideways only: the image moves
            place_orthographic_eye(cam, lo, hi);
        }
        return cam;
    }
    if (!sc.position && !sc.target)
        return frame_points(frame_samples(nodes),
                            {.azimuth = az, .altitude = alt, .fov = sc.fov, .width = sc.width, .height = sc.height, .fill = 0.9});
    Camera cam;
    if (sc.position) {
        const glm::dvec2 xy = parse_scene_position(*sc.position, meta, scene_file(scene));
        cam.eye = {xy.x, xy.y, *sc.elevation * scene.terrain.vertical_exaggeration};
    }
    if (sc.target) {
        const glm::dvec3 target = ground_point(scene, *sc.target, meta, nodes, lo, hi);
        if (sc.position) {  // aimed from the position at the target
            const glm::dvec3 d = target - cam.eye;
            if (!(glm::length(d) > 0.0)) throw Error("scene", scene_file(scene), "camera position and target coincide");
            const glm::dvec2 angles = angles_from_direction(glm::normalize(d));
            az = angles.x, alt = angles.y;
        } else {  // standing `distance` back from the target along the view direction
            const double distance = sc.distance.value_or(0.5 * glm::length(glm::dvec2(hi - lo)));
            cam.eye = target - direction_from_angles(az, alt) * distance;
        }
    }
    cam.azimuth = az, cam.altitude = alt, cam.fov = sc.fov;
    cam.width = sc.width, cam.height = sc.height;
    fit_depth_range(cam, lo, hi);
    return cam;
}

// Throws when a placed camera is at or below the ground under it.
void check_above_ground(const Scene& scene, const GridNodes& nodes, const Camera& cam) {
    double ground = 0.0;
    if ((scene.view.camera.position || scene.view.camera.target) && !is_orthographic(cam) && grid_ground_height(nodes, cam.eye.x, cam.eye.y, ground) && cam.eye.z <= ground) {
        std::ostringstream msg;
        msg << "camera is inside the terrain (elevation " << cam.eye.z / scene.terrain.vertical_exaggeration
            << " m, ground " << ground / scene.terrain.vertical_exaggeration << " m)";
        throw Error("scene", scene_file(scene), msg.str());
    }
}

void log_window(const Log& log, const GridWindow& w, int cols, int rows) {
    const std::size_t cells = std::size_t(w.cols() - 1) * (w.rows() - 1);
    const std::size_t all = std::size_t(cols - 1) * (rows - 1);
    log.info("modelled " + std::to_string(cells) + " of " + std::to_string(all) + " DEM cells (window " +
             std::to_string(w.c0) + ".." + std::to_string(w.c1 - 1) + " x " + std::to_string(w.r0) + ".." +
             std::to_string(w.r1 - 1) + ")");
}

// A map at a scale that leaves part of the DEM off the page says so on stderr, whatever --verbose:
// the rows and columns drawn (the view's window, grid nodes) and the map coordinates the image
// spans (its corners through the plan view's geotransform; an oblique view's window alone).
void warn_map_crop(const Scene& scene, const GridWindow& w, const Terrain& meta, const Camera& cam) {
    if (!(scene.view.map_scale > 0.0)) return;
    if (w.c0 <= 0 && w.r0 <= 0 && w.c1 >= meta.cols && w.r1 >= meta.rows) return;
    std::ostringstream s;
    s << "penink: warning: at 1:" << map_scale_text(scene.view.map_scale) << " the map shows part of the DEM: rows "
      << std::max(w.r0, 0) << ".." << std::min(w.r1, meta.rows) - 1 << " and columns " << std::max(w.c0, 0) << ".."
      << std::min(w.c1, meta.cols) - 1 << " of " << meta.rows << " x " << meta.cols;
    if (const auto g = plan_view_georeference(cam, meta.origin, meta.crs_wkt)) {
        const glm::dvec2 a = map_point(*g, 0.0, 0.0), b = map_point(*g, cam.width, cam.height);
        s << " (map x " << format_number(std::min(a.x, b.x), 1) << " to " << format_number(std::max(a.x, b.x), 1) << ", y "
          << format_number(std::min(a.y, b.y), 1) << " to " << format_number(std::max(a.y, b.y), 1) << ")";
    }
    s << "; a smaller scale (--scale) or a larger --page shows more";
    std::cerr << s.str() << "\n";
}

// Bounds of the whole stored terrain as drawn: exactly the drawn nodes' (the largest and
// smallest stored heights scale to the largest and smallest drawn ones; water raises both to
// the sea's height at most).
void stored_bounds(const SceneTerrain& terrain, glm::dvec3& lo, glm::dvec3& hi) {
    const StoredTerrain& t = terrain.stored;
    const double e = terrain.exaggeration;
    const GridNodes nodes = terrain.nodes();
    const auto drawn = [&](float z) {
        const float d = float(double(z) * e);
        return double(nodes.has_sea() ? std::max(d, nodes.sea_z()) : d);
    };
    lo = glm::dvec3(t.plan_lo, drawn(t.lod.z_min));
    hi = glm::dvec3(t.plan_hi, drawn(t.lod.z_max));
}

}  // namespace

std::vector<glm::dvec3> frame_samples(const GridNodes& t) {
    std::vector<glm::dvec3> pts;
    if (t.cols <= 0 || t.rows <= 0) return pts;
    // nodes i0, i0 + every, ... (< i1) as drawn, read without keeping their blocks (a terrain
    // cache's nodes: the frame of a large DEM touches a node or two in most blocks)
    const auto read = [&t](std::size_t i0, std::size_t i1, std::size_t every, std::vector<glm::vec3>& pos,
                           std::vector<std::uint8_t>& valid) {
        const std::size_t n = i1 > i0 ? (i1 - i0 + every - 1) / every : 0;
        pos.resize(n), valid.resize(n);
        t.read_strided(i0, i1, every, pos.data(), valid.data());
    };
    std::vector<glm::vec3> pa, pb;
    std::vector<std::uint8_t> va, vb;
    const auto add = [&](std::size_t j, const std::vector<glm::vec3>& pos, const std::vector<std::uint8_t>& valid) {
        if (valid[j]) pts.emplace_back(t.drawn(pos[j]));
    };
    constexpr std::size_t enough = 20000;  // enough to frame by
    if (t.size() <= enough) {
        read(0, t.size(), 1, pa, va);
        for (std::size_t j = 0; j < pa.size(); ++j) add(j, pa, va);
    } else {
        // every k-th node of every k-th row: a frame reads 1/k of the rows
        const int k = int(std::ceil(std::sqrt(double(t.size()) / double(enough))));
        for (int r = 0; r < t.rows; r += k) {
            read(t.index(0, r), t.index(0, r) + std::size_t(t.cols), std::size_t(k), pa, va);
            for (std::size_t j = 0; j < pa.size(); ++j) add(j, pa, va);
        }
    }
    // the edges decide the frame: keep all of them (the first and last row node by node, then
    // the first and last column)
    read(t.index(0, 0), t.index(0, 0) + std::size_t(t.cols), 1, pa, va);
    read(t.index(0, t.rows - 1), t.index(0, t.rows - 1) + std::size_t(t.cols), 1, pb, vb);
    for (std::size_t c = 0; c < pa.size(); ++c) add(c, pa, va), add(c, pb, vb);
    pa.resize(std::size_t(t.rows)), va.resize(pa.size()), pb.resize(pa.size()), vb.resize(pa.size());
    t.read_column(0, pa.data(), va.data());
    t.read_column(t.cols - 1, pb.data(), vb.data());
    for (std::size_t r = 0; r < pa.size(); ++r) add(r, pa, va), add(r, pb, vb);
    return pts;
}

std::vector<glm::dvec3> frame_samples(const Terrain& t) { return frame_samples(grid_nodes(t)); }

void resolve_vertical_exaggeration(Scene& scene, double z_min, double z_max, const glm::dvec2& plan_lo,
                                   const glm::dvec2& plan_hi, const Log& log) {
    if (!scene.terrain.exaggeration_auto) return;
    if (scene.terrain.sea_level) z_min = std::max(z_min, *scene.terrain.sea_level);  // the sea floor is not drawn
    const double relief = std::max(z_max - z_min, 0.0), extent = std::max(plan_hi.x - plan_lo.x, plan_hi.y - plan_lo.y);
    scene.terrain.vertical_exaggeration = auto_vertical_exaggeration(relief, extent);
    scene.terrain.exaggeration_auto = false;
    scene.terrain.exaggeration_was_auto = true;
    log.info(describe_auto_exaggeration(relief, extent, scene.terrain.vertical_exaggeration));
}

Terrain read_scene_dem(Scene& scene, const Log& log) {
    if (scene.terrain.exaggeration_auto) {  // read at 1 to find the relief; read again only when it is not 1
        Terrain flat = read_dem(scene.source.dem);
        glm::dvec3 lo, hi;
        if (!terrain_bounds(flat, lo, hi)) lo = hi = glm::dvec3(0.0);
        resolve_vertical_exaggeration(scene, flat.elevation_min, flat.elevation_max, glm::dvec2(lo), glm::dvec2(hi), log);
        if (scene.terrain.vertical_exaggeration == 1.0) {
            if (const std::string w = missing_crs_warning(flat); !w.empty()) std::cerr << w << "\n";
            return flat;
        }
    }
    DemOptions options;
    options.vertical_exaggeration = scene.terrain.vertical_exaggeration;
    Terrain dem = read_dem(scene.source.dem, options);
    if (const std::string w = missing_crs_warning(dem); !w.empty()) std::cerr << w << "\n";
    return dem;
}

std::string terrain_cache_path(const std::string& dem_path, const std::string& cache_dir) {
    std::string path = drainage_cache_path(dem_path, cache_dir);
    if (path.size() >= 3 && path.compare(path.size() - 3, 3, ".dv") == 0) path.resize(path.size() - 3);
    return path + ".lod";
}

TerrainCacheKey terrain_cache_key(const std::string& dem_path) {
    const std::uint64_t identity = dem_file_identity(dem_path);  // before the read: a write meanwhile changes it
    const DrainageFingerprint f = dem_fingerprint(dem_path, 1);
    return {f.file_size, f.mtime_ns, f.content_hash, 0, true, identity};
}

std::optional<TerrainCacheKey> known_terrain_key(const std::string& dem_path, const std::string& cache_dir) {
    const std::uint64_t identity = dem_file_identity(dem_path);
    if (identity == 0) return std::nullopt;
    for (const std::string& p : {dem_path + ".lod", terrain_cache_path(dem_path, cache_dir)})
        if (std::optional<TerrainCacheKey> k = recorded_terrain_key(p); k && k->identity == identity) return k;
    return std::nullopt;
}

StoredTerrain open_stored_terrain(const std::string& dem_path, const Log& log, const std::string& cache_dir, bool announce,
                                  const TerrainCacheKey* known) {
    auto t0 = Clock::now();
    const std::string path = terrain_cache_path(dem_path, cache_dir);
    auto hashed_key = [&] {
        try {
            return terrain_cache_key(dem_path);
        } catch (const Error&) {  // the reader names what is wrong with the file
            read_dem(dem_path);
            throw;
        }
    };
    const std::optional<TerrainCacheKey> unchanged = known ? std::nullopt : known_terrain_key(dem_path, cache_dir);
    TerrainCacheKey key = known ? *known : unchanged ? *unchanged : hashed_key();
    std::string why;
    // Beside the DEM first (where `penink drainage` left it, in a folder render may not write),
    // then where render keeps it.
    for (const std::string& p : {dem_path + ".lod", path}) {
        if (p != path && !std::filesystem::exists(p)) continue;
        if (std::optional<StoredTerrain> cached = read_terrain_cache(p, key, &why)) {
            cached->meta.source = dem_path, cached->key = key;
            // the DEM hashed because no cache recorded its identity (moved or copied with its
            // cache, its status changed): its identity now recorded, so the next render does not
            // read it again; only in the cache this render keeps (never one beside the DEM where
            // it writes none: where penink is installed, its examples stay untouched)
            if (p == path && !known && !unchanged && key.identity != 0) record_terrain_identity(p, key.identity);
            log.info("terrain: using cached " + p + " (" + cache_file_size(p) + ", " + std::to_string(cached->meta.cols) + "x" +
                     std::to_string(cached->meta.rows) + " nodes, " + std::to_string(int(ms_since(t0))) + " ms)");
            return std::move(*cached);
        }
        if (p == path) break;
    }
    log.info("terrain: " + path + ": " + why + "; building");
    if (unchanged) key = hashed_key();  // a build is keyed by the DEM's bytes, never by a recorded key
    const bool occupied = occupied_by_other_than_file(path);  // a FIFO, a folder: neither read nor replaced
    if (occupied)
        std::cerr << "penink: warning: terrain: " << path
                  << ": not a regular file; the terrain cache is neither read nor written (built in memory)\n";
    const DemSize size = read_dem_size(dem_path);
    const double side = std::ldexp(1.0, lod_padded_levels(size.cols, size.rows)) + 1.0;
    // Before a read: a long thin DEM's pyramid covers the padded square (terrain_lod.hpp).
    auto check = [&](const char* how, double need) {
        check_memory("surface", dem_path,
                     std::string(how) + " of the DEM's " + std::to_string(size.cols) + "x" +
                         std::to_string(size.rows) + " nodes (" + std::to_string(std::int64_t(side)) + "^2 padded nodes)",
                     need, memory_budget(0));
    };
    if (!occupied) check("building the terrain cache", terrain_cache_estimate(size.cols, size.rows).peak_bytes);
    if (announce) announce_cache_build(std::cerr, CacheKind::terrain, size.cols, size.rows);
    StageProgress progress(std::cerr, log.progress, "building terrain cache");
    progress.update("reading the DEM", 0.0);
    bool unwritable = false;  // the streamed build could not write the file: the fallback does not try again
    if (!occupied) {  // streamed: the heights and the pyramid's strips, never the positions or the whole pyramid
        bool built = false;
        try {
            built = build_terrain_cache(dem_path, path, key, [&](int stage) {
                if (stage == 0) {
                    log.info("read " + dem_path + ": " + std::to_string(size.cols) + "x" + std::to_string(size.rows) +
                             " nodes (" + std::to_string(int(lap_ms(t0))) + " ms)");
                    progress.update("level-of-detail pyramid", 0.4);
                    return;
                }
                log.info("level-of-detail pyramid: " + std::to_string((1 << lod_padded_levels(size.cols, size.rows)) + 1) +
                         "^2 nodes (" + std::to_string(int(lap_ms(t0))) + " ms)");
                progress.update("writing", 0.8);
            });
        } catch (const Error& e) {
            if (e.stage() != "surface") throw;  // the DEM's own errors
            log.info(std::string(e.what()) + "; using the terrain built in memory");
            unwritable = true;
        }
        if (built) {
            log.info("terrain: wrote " + path + " (" + cache_file_size(path) + ", " + std::to_string(int(lap_ms(t0))) + " ms)");
            if (std::optional<StoredTerrain> mapped = read_terrain_cache(path, key)) {
                progress.update("done", 1.0);
                mapped->meta.source = dem_path, mapped->key = key;  // the drainage fingerprint's too
                return std::move(*mapped);
            }
        }
    }
    check("the level-of-detail pyramid",
          size.nodes() * (render_bytes_per_node + lod_bytes_per_node) + lod_errors_bytes(size.cols, size.rows));
    Terrain flat = read_dem(dem_path);
    log.info("read " + dem_path + ": " + std::to_string(flat.cols) + "x" + std::to_string(flat.rows) + " nodes (" +
             std::to_string(int(lap_ms(t0))) + " ms)");
    progress.update("level-of-detail pyramid", 0.4);
    StoredTerrain stored = store_terrain(std::move(flat));
    stored.key = key;
    log.info("level-of-detail pyramid: " + std::to_string(stored.lod.side()) + "^2 nodes (" +
             std::to_string(int(lap_ms(t0))) + " ms)");
    progress.update("writing", 0.8);
    if (occupied || unwritable) {
        progress.update("done", 1.0);
        return stored;
    }
    try {
        write_terrain_cache(path, stored, key);
        log.info("terrain: wrote " + path + " (" + cache_file_size(path) + ", " + std::to_string(int(lap_ms(t0))) + " ms)");
    } catch (const Error& e) {
        log.info(std::string(e.what()) + "; using the terrain built in memory");
        progress.update("done", 1.0);
        return stored;
    }
    progress.update("done", 1.0);
    // Drawn from the file as a warm render would (the same values), so the memory held is the
    // nodes and pyramid, not the whole DEM read, while a drainage build that follows holds its own copy.
    if (std::optional<StoredTerrain> mapped = read_terrain_cache(path, key)) {
        mapped->meta.source = dem_path, mapped->key = key;
        return std::move(*mapped);
    }
    return stored;
}

SceneTerrain open_scene_terrain(Scene& scene, const Log& log) {
    return scene_terrain(scene, open_stored_terrain(scene.source.dem, log, scene.terrain.cache_dir), log);
}

SceneTerrain scene_terrain(Scene& scene, StoredTerrain stored, const Log& log, const TerrainLod* sea_pyramid) {
    resolve_vertical_exaggeration(scene, stored.lod.z_min, stored.lod.z_max, stored.plan_lo, stored.plan_hi, log);
    const double e = scene.terrain.vertical_exaggeration;
    if (!std::isfinite(e) || e <= 0.0) throw Error("scene", scene_file(scene), "vertical exaggeration must be > 0");
    SceneTerrain t{std::move(stored), e, scene_file(scene)};
    if (scene.terrain.sea_level) {
        t.sea_level = *scene.terrain.sea_level;
        // Water over part or all of the DEM: the pyramid of the clamped nodes (terrain_lod.hpp),
        // so the flat sea takes no triangles and the pyramid's bounds hold the water drawn (a
        // DEM wholly under water is framed and seen at the sea's height); O(nodes) once per
        // command, held in memory.
        const TerrainLod& dry = t.stored.lod;
        if (t.sea_level > double(dry.z_min) && sea_pyramid && sea_pyramid->sea_level == t.sea_level) {
            t.stored.lod = *sea_pyramid;
        } else if (t.sea_level > double(dry.z_min)) {
            const Clock::time_point t0 = Clock::now();
            t.stored.lod = build_terrain_lod(t.stored.drawn(1.0, t.sea_level), 1.0);
            std::ostringstream msg;
            msg << "level of detail: pyramid rebuilt for the sea level " << t.sea_level << " m (" << int(ms_since(t0))
                << " ms)";
            log.info(msg.str());
        }
    }
    if (const std::string w = missing_crs_warning(t.stored.meta); !w.empty()) std::cerr << w << "\n";
    return t;
}

Camera scene_camera(const Scene& scene, const SceneTerrain& terrain) {
    glm::dvec3 lo, hi;
    stored_bounds(terrain, lo, hi);
    return place_camera(scene, terrain.stored.meta, terrain.nodes(), lo, hi);
}

Camera scene_camera(const Scene& scene, const Terrain& terrain) {
    glm::dvec3 lo, hi;
    terrain_bounds(terrain, lo, hi);
    return place_camera(scene, terrain, grid_nodes(terrain), lo, hi);
}

FrameTerrain frame_terrain(Terrain terrain) {
    auto owned = std::make_shared<Terrain>(std::move(terrain));
    FrameTerrain f;
    f.nodes = grid_nodes(*owned);
    f.lod = build_terrain_lod(*owned);
    f.window = {0, 0, owned->cols, owned->rows};
    terrain_bounds(*owned, f.lo, f.hi);
    f.meta = terrain_metadata(*owned);
    f.storage = std::move(owned);
    return f;
}

Terrain window_terrain(const FrameTerrain& f) { return crop_nodes(f.meta, f.nodes, f.window); }

LodView scene_view_window(const SceneTerrain& terrain, const Camera& cam) {
    const StoredTerrain& s = terrain.stored;
    LodView v = lod_visible_window(s.lod, terrain.nodes(), terrain.exaggeration, cam);
    if (v.window.cols() < 2 || v.window.rows() < 2) return {};
    GridWindow& w = v.window;
    w.c0 = std::max(w.c0 - 1, 0), w.r0 = std::max(w.r0 - 1, 0);  // a node of margin
    w.c1 = std::min(w.c1 + 1, s.meta.cols), w.r1 = std::min(w.r1 + 1, s.meta.rows);
    glm::dvec3 lo, hi;
    stored_bounds(terrain, lo, hi);
    if (w.c0 == 0 && w.r0 == 0 && w.c1 == s.meta.cols && w.r1 == s.meta.rows) v.lo = lo, v.hi = hi;
    else v.lo = glm::max(v.lo, lo), v.hi = glm::min(v.hi, hi);
    return v;
}

LodView view_union(const SceneTerrain& terrain, const std::vector<LodView>& views, bool whole) {
    const StoredTerrain& s = terrain.stored;
    LodView u;
    if (whole) {
        u.window = {0, 0, s.meta.cols, s.meta.rows};
        stored_bounds(terrain, u.lo, u.hi);
        return u;
    }
    bool any = false;
    for (const LodView& v : views) {
        if (v.window.cols() < 2 || v.window.rows() < 2) continue;
        if (!any) {
            u = v, any = true;
            continue;
        }
        GridWindow& w = u.window;
        w.c0 = std::min(w.c0, v.window.c0), w.r0 = std::min(w.r0, v.window.r0);
        w.c1 = std::max(w.c1, v.window.c1), w.r1 = std::max(w.r1, v.window.r1);
        u.lo = glm::min(u.lo, v.lo), u.hi = glm::max(u.hi, v.hi);
    }
    return u;
}

FrameTerrain frame_terrain(const SceneTerrain& terrain, const LodView& view) {
    FrameTerrain f;
    f.meta = terrain.meta();
    f.nodes = terrain.nodes();
    f.lod = terrain.stored.lod;
    f.storage = terrain.stored.storage;
    f.window = view.window;
    f.lo = view.lo, f.hi = view.hi;
    return f;
}

FrameTerrain terrain_for_view(const SceneTerrain& terrain, Camera& cam, const Scene& scene, const Log& log) {
    check_above_ground(scene, terrain.nodes(), cam);
    const LodView v = scene_view_window(terrain, cam);
    if (v.window.cols() < 2 || v.window.rows() < 2)
        throw Error("scene", scene_file(scene), "the camera sees no part of the DEM");
    log_window(log, v.window, terrain.stored.meta.cols, terrain.stored.meta.rows);
    fit_depth_range(cam, v.lo, v.hi);
    warn_map_crop(scene, v.window, terrain.stored.meta, cam);
    return frame_terrain(terrain, v);
}

Terrain terrain_for_view(Terrain terrain, Camera& cam, const Scene& scene, const Log& log) {
    check_above_ground(scene, grid_nodes(terrain), cam);
    const GridWindow w = visible_window(terrain, view_projection(cam), 1);
    if (w.cols() < 2 || w.rows() < 2)
        throw Error("scene", scene_file(scene), "the camera sees no part of the DEM");
    const bool whole = w.c0 == 0 && w.r0 == 0 && w.c1 == terrain.cols && w.r1 == terrain.rows;
    log_window(log, w, terrain.cols, terrain.rows);
    warn_map_crop(scene, w, terrain, cam);
    Terrain view = whole ? std::move(terrain) : crop_terrain(terrain, w);
    glm::dvec3 lo, hi;
    terrain_bounds(view, lo, hi);
    fit_depth_range(cam, lo, hi);
    return view;
}

}  // namespace penink
