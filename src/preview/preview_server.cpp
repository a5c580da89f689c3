#include "preview/preview_server.hpp"

#include <csignal>
#include <future>
#include <memory>
#include <pthread.h>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "preview/latest_worker.hpp"
#include "preview/page_files.hpp"
#include "preview/preview_access.hpp"
#include "preview/preview_session.hpp"

namespace penink {

const std::string& preview_page_file(const std::string& name) {
    for (const PageFile& f : preview_page_files())
        if (f.name == name) return f.text;
    throw std::out_of_range("no page file " + name);
}

namespace {

using json = nlohmann::json;

// Runs `work` on the worker (queued, or as the latest frame) and waits for it: its value, or
// nullopt when a newer latest task replaced it first. Exceptions come back to the caller.
template <class T>
std::optional<T> on_worker(LatestWorker& worker, std::function<T()> work, bool latest) {
    auto done = std::make_shared<std::promise<std::optional<T>>>();
    WorkerTask task;
    task.run = [done, work] {
        try {
            done->set_value(work());
        } catch (...) {
            done->set_exception(std::current_exception());
        }
    };
    task.dropped = [done] { done->set_value(std::nullopt); };
    if (latest) worker.submit_latest(std::move(task));
    else worker.submit(std::move(task));
    return done->get_future().get();
}

void send_json(httplib::Response& res, const json& j) { res.set_content(j.dump(), "application/json"); }

void send_error(httplib::Response& res, int status, const std::string& what) {
    res.status = status;
    send_json(res, json{{"error", what}});
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

}  // namespace

int serve_preview(const Scene& scene, const PreviewServerOptions& options, const Log& log, std::ostream& out) {
    // SIGINT and SIGTERM wait for the thread below (every thread made after this inherits the mask)
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT), sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    std::unique_ptr<PreviewSession> session;
    std::promise<void> ready;
    LatestWorker worker(
        [&] {
            try {
                session = std::make_unique<PreviewSession>(scene, options.save_path, options.gl, log);
                ready.set_value();
            } catch (...) {
                ready.set_exception(std::current_exception());
            }
        },
        [&] { session.reset(); });
    ready.get_future().get();
    const PreviewView initial = session->initial_view();
    const std::string save_path = session->save_path();

    httplib::Server server;
    const int port = options.port > 0 ? (server.bind_to_port("127.0.0.1", options.port) ? options.port : -1)
                                      : server.bind_to_any_port("127.0.0.1");
    if (port <= 0) throw Error("cli", "", "cannot listen on 127.0.0.1" + (options.port > 0 ? ":" + std::to_string(options.port) : ""));
    const std::string token = random_token();

    server.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
        if (!host_allowed(req.get_header_value("Host"), port) || !token_matches(req.get_param_value("token"), token)) {
            res.status = 403;
            res.set_content("forbidden\n", "text/plain");
            return httplib::Server::HandlerResponse::Handled;
        }
        res.set_header("Cache-Control", "no-store");
        return httplib::Server::HandlerResponse::Unhandled;
    });
    server.Get("/", [&](const httplib::Request&, httplib::Response& res) {
        std::string html = replace_all(preview_page_file("index.html"), "@CSS@", preview_page_file("preview.css"));
        res.set_content(replace_all(html, "@TOKEN@", token), "text/html; charset=utf-8");
    });
    server.Get("/preview.js", [&](const httplib::Request&, httplib::Response& res) {
        res.set_content(preview_page_file("preview.js"), "text/javascript; charset=utf-8");
    });
    server.Get("/view", [&](const httplib::Request&, httplib::Response& res) {
        send_json(res, json{{"view", view_json(initial)}, {"save", save_path}});
    });
    // A request's view over the starting one, or a 400 answer.
    const auto read_view = [&](const json& j, httplib::Response& res) -> std::optional<PreviewView> {
        try {
            return view_from_json(j, initial);
        } catch (const std::exception& e) {
            send_error(res, 400, e.what());
            return std::nullopt;
        }
    };
    const auto parse_body = [](const httplib::Request& req, httplib::Response& res) -> std::optional<json> {
        json j = json::parse(req.body, nullptr, false);
        if (j.is_discarded()) {
            send_error(res, 400, "the request is not JSON");
            return std::nullopt;
        }
        return j;
    };
    // Work on the drawing thread, its penink::Error as a 422 answer.
    const auto guarded = [&](httplib::Response& res, const std::function<void()>& f) {
        try {
            f();
        } catch (const Error& e) {
            send_error(res, 422, e.what());
        } catch (const std::exception& e) {
            send_error(res, 500, e.what());
        }
    };
    server.Post("/frame", [&](const httplib::Request& req, httplib::Response& res) {
        const auto body = parse_body(req, res);
        if (!body) return;
        const auto view = read_view(*body, res);
        if (!view) return;
        double scale = 1.0;
        if (req.has_param("scale")) scale = std::atof(req.get_param_value("scale").c_str());
        if (!(scale >= 0.05 && scale <= 1.0)) return send_error(res, 400, "scale must be between 0.05 and 1");
        guarded(res, [&] {
            const std::optional<PreviewFrame> frame =
                on_worker<PreviewFrame>(worker, [&, v = *view] { return session->draw(v, scale); }, true);
            if (!frame) return send_error(res, 409, "superseded by a newer view");
            res.set_header("X-Penink-Draw-Ms", std::to_string(frame->draw_ms));
            // Sent as it is: cpp-httplib compresses "image/svg+xml" (not this type with its
            // charset) with brotli when the browser accepts it, at a quality that takes seconds
            // for a frame's megabytes (about 9 s for volcano's 3 MB on a loaded 2-core machine),
            // where sending them over the loopback takes milliseconds.
            res.set_content(frame->svg, "image/svg+xml; charset=utf-8");
        });
    });
    server.Post("/locate", [&](const httplib::Request& req, httplib::Response& res) {
        const auto body = parse_body(req, res);
        if (!body) return;
        if (!body->is_object() || !body->contains("x") || !body->contains("y") || !body->at("x").is_number() ||
            !body->at("y").is_number())
            return send_error(res, 400, "locate takes {\"x\": pixel, \"y\": pixel}");
        const double x = body->at("x").get<double>(), y = body->at("y").get<double>();
        guarded(res, [&] {
            const auto point = *on_worker<std::optional<PreviewPoint>>(worker, [&] { return session->locate(x, y); }, false);
            if (!point) return send_json(res, json{{"hit", false}});
            json j{{"hit", true}, {"x", point->x}, {"y", point->y}, {"elevation", point->elevation}};
            if (point->lon) j["lon"] = *point->lon, j["lat"] = *point->lat;
            send_json(res, j);
        });
    });
    server.Post("/save", [&](const httplib::Request& req, httplib::Response& res) {
        const auto body = parse_body(req, res);
        if (!body) return;
        const auto view = read_view(*body, res);
        if (!view) return;
        guarded(res, [&] {
            const std::string path = *on_worker<std::string>(worker, [&] { return session->save(*view); }, false);
            send_json(res, json{{"saved", path}});
        });
    });
    server.Post("/export", [&](const httplib::Request& req, httplib::Response& res) {
        const auto body = parse_body(req, res);
        if (!body) return;
        if (!body->is_object() || !body->contains("formats") || !body->at("formats").is_array())
            return send_error(res, 400, "export takes {\"view\": {...}, \"formats\": [\"svg\", ...]}");
        std::vector<std::string> formats;
        for (const json& f : body->at("formats")) {
            static const std::vector<std::string> known = {"svg", "pdf", "ps", "eps", "png", "tif", "jpg", "webp", "exr"};
            if (!f.is_string() || std::find(known.begin(), known.end(), f.get<std::string>()) == known.end())
                return send_error(res, 400, "formats are svg, pdf, ps, eps, png, tif, jpg, webp, exr");
            formats.push_back(f.get<std::string>());
        }
        if (formats.empty()) return send_error(res, 400, "no format chosen");
        const auto view = read_view(body->value("view", json::object()), res);
        if (!view) return;
        guarded(res, [&] {
            const auto paths = *on_worker<std::vector<std::string>>(
                worker, [&] { return session->export_files(*view, formats); }, false);
            send_json(res, json{{"exported", paths}});
        });
    });

    std::thread stopper([&] {
        int signal = 0;
        sigwait(&stop_signals, &signal);
        server.stop();
    });
    out << "penink preview: http://127.0.0.1:" << port << "/?token=" << token << std::endl;
    server.listen_after_bind();
    if (stopper.joinable()) {
        pthread_kill(stopper.native_handle(), SIGTERM);  // when listening ended otherwise
        stopper.join();
    }
    return 0;
}

}  // namespace penink
