#include "scene/scene_style.hpp"

namespace penink {

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
