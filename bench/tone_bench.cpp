// The tone measure of a terrain drawing (lines/tone_measure.hpp): draws INPUT as `penink render`
// does (scene, style, finishing, the CPU rasteriser of the PNG writer), then prints r and SSIM of
// the blurred ink against the target tone 1 - n.l at sigma 4 and 8 px, the mean ink against the
// target's, the ink per unit of drawn terrain in the near, middle and far thirds of depth, and the
// frame's time with the hachures' share.
// Usage: tone_bench INPUT [--map] [--width W] [--height H] [--style NAME] [--no-hachures]
//        [--set KEY=VALUE ...] (a [hachures] key, e.g. contrast=2) [--ink ink.png] [--target target.png]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>

#include "export/rasterise.hpp"
#include "export/styled_drawing.hpp"
#include "lines/finish_drawing.hpp"
#include "lines/tone_measure.hpp"
#include "render/gl_context.hpp"
#include "scene/hachure_lines.hpp"
#include "scene/scene_style.hpp"
#include "scene/terrain_frames.hpp"

using namespace penink;

namespace {

void write_png(const std::string& path, int w, int h, const std::vector<unsigned char>& rgb) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return;
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    out->open(path, spec);
    out->write_image(OIIO::TypeDesc::UINT8, rgb.data());
    out->close();
}

std::vector<unsigned char> grey(const ToneImage& t) {  // ink 0 white .. 1 black; no value: light blue
    std::vector<unsigned char> rgb(t.v.size() * 3);
    for (std::size_t i = 0; i < t.v.size(); ++i) {
        const bool ok = std::isfinite(t.v[i]);
        const int g = ok ? int(std::lround(255.0 * (1.0 - std::clamp(double(t.v[i]), 0.0, 1.0)))) : 0;
        rgb[3 * i] = ok ? g : 220, rgb[3 * i + 1] = ok ? g : 230, rgb[3 * i + 2] = ok ? g : 255;
    }
    return rgb;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: tone_bench INPUT [--map] [--width W] [--height H] [--style NAME] [--no-hachures] "
                             "[--set KEY=VALUE] [--ink PNG] [--target PNG]\n");
        return 2;
    }
    try {
        std::string style_name;  // --style: the scene's [style] table goes over it
        for (int i = 2; i + 1 < argc; ++i)
            if (std::string(argv[i]) == "--style") style_name = argv[i + 1];
        Scene scene = load_scene(argv[1], style_name);
        std::string ink_png, target_png;
        for (int i = 2; i < argc; ++i) {
            const std::string a = argv[i];
            const auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
            if (a == "--map") {
                scene.view.camera.projection = Projection::orthographic;
                scene.view.camera.azimuth = 0.0, scene.view.camera.altitude = -90.0;
                scene.view.camera.position.reset(), scene.view.camera.elevation.reset();
            } else if (a == "--width") scene.view.camera.width = std::stoi(next());
            else if (a == "--height") scene.view.camera.height = std::stoi(next());
            else if (a == "--style") next();
            else if (a == "--no-hachures") scene.lines.hachures.enabled = false;
            else if (a == "--ink") ink_png = next();
            else if (a == "--target") target_png = next();
            else if (a == "--set") {
                const std::string kv = next();
                const std::size_t eq = kv.find('=');
                const std::string k = kv.substr(0, eq), v = kv.substr(eq + 1);
                HachureParams& h = scene.lines.hachures;
                if (k == "tone") hachure_tone_named(v, h.tone);
                else if (double* number = hachure_number(h, k)) *number = std::stod(v);
            } else {
                std::fprintf(stderr, "tone_bench: unknown option %s\n", a.c_str());
                return 2;
            }
        }
        validate_scene(scene);
        const Style& style = scene.style.resolved;
        auto context = make_gl_context();
        const Log log;
        SceneView view = open_terrain_view(scene, *context, log);
        auto* frames = dynamic_cast<TerrainFrames*>(view.frames.get());
        const auto t0 = std::chrono::steady_clock::now();
        SceneDrawing d = frames->draw(view.camera, scene);
        const double frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        d = frames->draw(view.camera, scene);  // warm: the second frame's time is the steady one
        const double warm_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() - frame_ms;
        for (LayerKind k : all_layers) {  // what the frame drew, per layer (before finishing)
            double len = 0.0;
            for (const Stroke& st : d.drawing.layer(k).strokes)
                for (std::size_t i = 1; i < st.points.size(); ++i) len += glm::length(st.points[i] - st.points[i - 1]);
            if (len > 0) std::printf("  %s: %zu strokes, %.0f px\n", std::string(layer_name(k)).c_str(), d.drawing.layer(k).strokes.size(), len);
        }
        finish_drawing(d.drawing, finish_options(style, scene.style.seed, true));
        const StyledDrawing styled = style_drawing(d.drawing, style);
        RasterTransform tr;
        tr.width = d.camera.width, tr.height = d.camera.height;
        const RgbImage rgb = rasterise(styled, tr);
        const ToneImage ink = ink_from_rgb(rgb.width, rgb.height, rgb.rgb);
        const GridNodes& n = frames->terrain().nodes;
        n.need(GridWindow{0, 0, n.cols, n.rows});  // the target reads every node directly (the frame may not have)
        ToneGrid grid{n.cols, n.rows, n.pos, n.valid, n.z_scale};
        if (n.has_sea()) grid.sea_z = n.sea_z();  // water: no target (tone_measure.hpp)
        const ToneImage target = target_tone(grid, d.camera, d.toward, light_vector(Light{scene.view.light.azimuth, scene.view.light.altitude}));
        std::printf("%s%s: %zu hachures, frame %.0f ms (warm %.0f ms, hachures %.0f ms)\n", argv[1],
                    is_orthographic(d.camera) ? " (orthographic)" : "", d.drawing.layer(LayerKind::hachures).strokes.size(),
                    frame_ms, warm_ms, d.hachure_ms);
        for (double sigma : {4.0, 8.0}) {
            const ToneScore s = tone_score(ink, target, sigma);
            std::printf("sigma %.0f px: r %.3f  SSIM %.3f  mean ink %.3f  target %.3f  (ink/target %.2f, %zu px)\n", sigma,
                        s.r, s.ssim, s.mean_ink, s.mean_target, s.mean_target > 0 ? s.mean_ink / s.mean_target : 0.0,
                        s.pixels);
        }
        {  // where the ink falls short: the unblurred mean ink, all layers and hachures alone, per tone band
            Drawing only = d.drawing;
            for (LayerKind k : all_layers)
                if (k != LayerKind::hachures) only.layer(k).strokes.clear(), only.layer(k).fill.clear();
            const RgbImage hrgb = rasterise(style_drawing(only, style), tr);
            const ToneImage hink = ink_from_rgb(hrgb.width, hrgb.height, hrgb.rgb);
            double count[5] = {}, all[5] = {}, hach[5] = {};
            for (std::size_t i = 0; i < target.v.size(); ++i) {
                if (!std::isfinite(target.v[i])) continue;
                const int b = std::clamp(int(target.v[i] * 5.0), 0, 4);
                count[b] += 1, all[b] += ink.v[i], hach[b] += hink.v[i];
            }
            double len = 0.0, terrain = 0.0;
            std::size_t shorter = 0;
            for (const Stroke& st : d.drawing.layer(LayerKind::hachures).strokes) {
                double l = 0.0;
                for (std::size_t i = 1; i < st.points.size(); ++i) l += glm::length(st.points[i] - st.points[i - 1]);
                len += l, shorter += l < 12.0;
            }
            for (float v : target.v) terrain += std::isfinite(v);
            std::printf("hachures: mean length %.1f px, %.0f %% under 12 px; length x width / terrain %.3f\n",
                        len / std::max<std::size_t>(1, d.drawing.layer(LayerKind::hachures).strokes.size()),
                        100.0 * shorter / std::max<std::size_t>(1, d.drawing.layer(LayerKind::hachures).strokes.size()),
                        len * hachure_pen(scene.lines.hachures, style).width_px / std::max(terrain, 1.0));
            std::printf("target band   share  ink (all)  ink (hachures)\n");
            double total = 0;
            for (double v : count) total += v;
            for (int b = 0; b < 5; ++b)
                if (count[b] > 0)
                    std::printf("  %.1f-%.1f   %5.3f  %9.3f  %14.3f\n", b / 5.0, (b + 1) / 5.0, count[b] / total, all[b] / count[b], hach[b] / count[b]);
        }
        const auto thirds = ink_by_depth_thirds(ink, target, d.toward);
        std::printf("ink per terrain pixel near %.3f  middle %.3f  far %.3f  (near/far %.2f)\n", thirds[0], thirds[1],
                    thirds[2], thirds[2] > 0 ? thirds[0] / thirds[2] : 0.0);
        const auto asked = ink_by_depth_thirds(target, target, d.toward);  // the target's own thirds
        std::printf("target per terrain pixel near %.3f  middle %.3f  far %.3f  (near/far %.2f)\n", asked[0], asked[1],
                    asked[2], asked[2] > 0 ? asked[0] / asked[2] : 0.0);
        if (!ink_png.empty()) write_png(ink_png, rgb.width, rgb.height, rgb.rgb);
        if (!target_png.empty()) write_png(target_png, target.width, target.height, grey(target));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tone_bench: %s\n", e.what());
        return 2;
    }
    return 0;
}
