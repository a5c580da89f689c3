#include "scene/plan_directions.hpp"

#include "core/georeference.hpp"
#include "input/dem_reader.hpp"

namespace penink {

std::vector<LayerDirections> plan_view_directions(const Drawing& drawing, const std::string& dem_path) {
    std::vector<LayerDirections> out;
    if (!drawing.georeference) return out;
    const LayerKind kinds[] = {LayerKind::creases, LayerKind::ridges};
    bool any = false;
    for (LayerKind k : kinds) any = any || !drawing.layer(k).strokes.empty();
    if (!any) return out;
    Terrain t = read_dem(dem_path);
    const glm::dvec2 origin = t.origin;
    const FallLineField field(std::move(t));
    for (LayerKind k : kinds) {
        const Layer& layer = drawing.layer(k);
        if (layer.strokes.empty()) continue;
        std::vector<std::vector<glm::dvec2>> lines;
        for (const Stroke& s : layer.strokes) {
            std::vector<glm::dvec2> l;
            l.reserve(s.points.size());
            for (const glm::vec2& p : s.points) l.push_back(map_point(*drawing.georeference, p.x, p.y) - origin);
            lines.push_back(std::move(l));
        }
        out.push_back({k, stroke_directions(lines, field)});
    }
    return out;
}

}  // namespace penink
