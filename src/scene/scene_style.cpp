#include "scene/scene_style.hpp"

namespace penink {

Style scene_style(const Scene& scene) {
    Style style = resolve_style(scene.style);
    if (scene.style_overrides.is_table()) apply_style_overrides(style, scene.style_overrides, scene.file);
    return style;
}

void apply_object_sketch(Scene& scene, const Style& style) {
    const LayerStyle &creases = style.layer(LayerKind::creases), &ridges = style.layer(LayerKind::ridges);
    scene.crease_sketch_px = float(creases.sketch), scene.crease_repeat = creases.repeat;
    scene.ridge_sketch_px = float(ridges.sketch), scene.ridge_repeat = ridges.repeat;
    // the hachures' spacing is computed for the pen that draws them (millimetres at 96 dpi)
    const double px = style.widths_mm ? 96.0 / 25.4 : 1.0;
    if (scene.hachures.width_px <= 0.0) scene.hachures.width_px = style.layer(LayerKind::hachures).width * px;
    // and the range its width takes with the tone (the layer's weight factors)
    scene.hachures.weight_min = style.layer(LayerKind::hachures).weight_min;
    scene.hachures.weight_max = style.layer(LayerKind::hachures).weight_max;
    // its taper and the ink of the lines it yields to, which the coverage feedback counts
    scene.hachures.taper_px = style.layer(LayerKind::hachures).taper * px;
    scene.hachures.taper_min = style.layer(LayerKind::hachures).taper_min;
    for (std::size_t i = 0; i < hachure_obstacle_layers.size(); ++i) {
        const LayerStyle& ls = style.layer(hachure_obstacle_layers[i]);
        scene.hachures.obstacle_pens[i] = HachurePen{ls.width * px, ls.weight_min, ls.weight_max, ls.taper * px, ls.taper_min};
    }
}

FinishOptions finish_options(const Style& style, std::uint64_t seed, bool object_space_terrain_lines) {
    FinishOptions f;
    f.seed = seed;
    f.near = float(style.near), f.far = float(style.far);
    for (LayerKind k : all_layers) {
        const LayerStyle& ls = style.layer(k);
        LayerFinish& lf = f.layer(k);
        lf.sketch = float(ls.sketch), lf.overshoot = float(ls.overshoot);
        lf.repeat = ls.repeat, lf.keep_far = float(ls.keep_far), lf.min_length = float(ls.min_length);
        if (object_space_terrain_lines && (k == LayerKind::creases || k == LayerKind::ridges))
            lf.space = SketchSpace::object;
        lf.occlusion_joins = k == LayerKind::silhouettes;
        // doubled lines merged, but for the hachures: parallel at 1.6 px on purpose, spaced by
        // their own placement (lines/hachures.hpp)
        lf.merge_px = k == LayerKind::hachures ? 0.0f : 1.5f;
    }
    return f;
}

}  // namespace penink
