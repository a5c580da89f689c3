#include "core/drawing.hpp"

namespace penink {

std::string_view layer_name(LayerKind kind) {
    switch (kind) {
        case LayerKind::surface: return "surface";
        case LayerKind::coastline: return "coastline";
        case LayerKind::hachures: return "hachures";
        case LayerKind::ridges: return "ridges";
        case LayerKind::creases: return "creases";
        case LayerKind::pels: return "pels";
        case LayerKind::textures: return "textures";
        case LayerKind::feature_edges: return "feature-edges";
        case LayerKind::silhouettes: return "silhouettes";
        case LayerKind::neatline: return "neatline";
        case LayerKind::grid: return "grid";
        case LayerKind::scale_bar: return "scale-bar";
        case LayerKind::north_arrow: return "north-arrow";
        case LayerKind::title: return "title";
    }
    return "unknown";
}

Drawing::Drawing() {
    for (size_t i = 0; i < layers.size(); ++i) layers[i].kind = all_layers[i];
}

}  // namespace penink
