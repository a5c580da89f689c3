// `penink preview`: a web page on 127.0.0.1 that draws a terrain scene live (preview_session.hpp)
// and steers its view (preview_view.hpp). cpp-httplib serves, on a free port (or the one asked
// for), the page (page/index.html with page/preview.css), its script (page/preview.js) and:
//   GET  /view     the starting view (JSON) and the file Save writes
//   POST /frame    a view (JSON; ?scale=S draws S of its size) -> the SVG; 409 when a newer
//                  request replaced it before it was drawn, 422 with the reason when the scene
//                  cannot be drawn so (the camera under the ground, ...)
//   POST /locate   {x, y} pixel of the last full-size frame -> {x, y, elevation, lon, lat}
//   POST /save     a view -> the scene file written
//   POST /export   {view, formats: ["svg", "pdf", ...]} -> the files written (all or none)
// Every request must name the server's Host (preview_access.hpp) and carry ?token=TOKEN, else
// 403; any other path is 404. One worker thread owns the OpenGL context and draws every frame
// (latest_worker.hpp): frame requests that arrive while one is drawn collapse to the newest.
#pragma once
#include <functional>
#include <ostream>
#include <string>

#include "core/log.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"

namespace penink {

struct PreviewServerOptions {
    int port = 0;           // 0: a free port
    std::string save_path;  // Save's file; Export's files share its name
    GlBackend gl = GlBackend::osmesa;
};

// Draws the scene's first frame, then prints "penink preview: http://127.0.0.1:PORT/?token=T" to
// `out` and serves until SIGINT or SIGTERM; returns 0. Throws penink::Error when the scene
// cannot be drawn or the port cannot be bound.
int serve_preview(const Scene& scene, const PreviewServerOptions& options, const Log& log, std::ostream& out);

}  // namespace penink
