#include "preview/preview_view.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/drawing.hpp"
#include "core/toml_file.hpp"
#include "scene/scene.hpp"

namespace penink {

namespace {

using json = nlohmann::json;

double number_in(const json& j, const char* key, double value, double lo, double hi) {
    if (!j.contains(key)) return value;
    const json& v = j.at(key);
    if (!v.is_number()) throw std::invalid_argument(std::string(key) + " must be a number");
    const double x = v.get<double>();
    if (!(x >= lo && x <= hi))
        throw std::invalid_argument(std::string(key) + " must be between " + toml_number(lo) + " and " + toml_number(hi));
    return x;
}

// A table's keys, sorted: the plain values first, then the tables ([name.sub]).
void write_table(std::ostringstream& o, const std::string& name, const toml::table& t) {
    std::vector<std::string> keys, tables;
    for (const auto& [k, v] : t) (v.is_table() ? tables : keys).push_back(k);
    std::sort(keys.begin(), keys.end());
    std::sort(tables.begin(), tables.end());
    if (!name.empty() && (!keys.empty() || tables.empty())) o << "\n[" << name << "]\n";
    for (const std::string& k : keys) {
        const toml::value& v = t.at(k);
        o << toml::format_key(k) << " = " << (v.is_floating() ? toml_number(v.as_floating()) : toml::format(v, 0)) << "\n";
    }
    for (const std::string& k : tables)
        write_table(o, name.empty() ? toml::format_key(k) : name + "." + toml::format_key(k), t.at(k).as_table());
}

toml::table& table_at(toml::table& t, const std::string& key) {
    if (!t.count(key) || !t.at(key).is_table()) t[key] = toml::table{};
    return t.at(key).as_table();
}

}  // namespace

std::string toml_number(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, value);
    std::string s(buf, r.ptr);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

json view_json(const PreviewView& v) {
    json j;
    j["orthographic"] = v.orthographic;
    j["target_x"] = v.target_x, j["target_y"] = v.target_y, j["distance"] = v.distance;
    j["azimuth"] = v.azimuth, j["altitude"] = v.altitude, j["fov"] = v.fov;
    j["width"] = v.width, j["height"] = v.height;
    j["light_azimuth"] = v.light_azimuth, j["light_altitude"] = v.light_altitude;
    j["vertical_exaggeration"] = v.vertical_exaggeration;
    j["crease_min_score"] = v.crease_min_score, j["ridge_min_score"] = v.ridge_min_score;
    j["hachure_spacing_min"] = v.hachure_spacing_min, j["hachure_spacing_max"] = v.hachure_spacing_max;
    j["style"] = v.style;
    json layers = json::object();
    for (LayerKind k : all_layers) {
        const std::string name(layer_name(k));
        const auto it = v.visible.find(name);
        layers[name] = it == v.visible.end() || it->second;
    }
    j["layers"] = layers;
    return j;
}

PreviewView view_from_json(const json& j, const PreviewView& view) {
    if (!j.is_object()) throw std::invalid_argument("the view must be a JSON object");
    PreviewView v = view;
    v.target_x = number_in(j, "target_x", v.target_x, -1e12, 1e12);
    v.target_y = number_in(j, "target_y", v.target_y, -1e12, 1e12);
    v.distance = number_in(j, "distance", v.distance, 1e-3, 1e8);
    v.azimuth = number_in(j, "azimuth", v.azimuth, -360.0, 360.0);
    v.altitude = number_in(j, "altitude", v.altitude, -90.0, 90.0);
    v.fov = number_in(j, "fov", v.fov, 1.0, 170.0);
    v.width = int(number_in(j, "width", v.width, 16, max_image_side));
    v.height = int(number_in(j, "height", v.height, 16, max_image_side));
    v.light_azimuth = number_in(j, "light_azimuth", v.light_azimuth, -360.0, 360.0);
    v.light_altitude = number_in(j, "light_altitude", v.light_altitude, 0.0, 90.0);
    v.vertical_exaggeration = number_in(j, "vertical_exaggeration", v.vertical_exaggeration, 0.01, max_vertical_exaggeration);
    v.crease_min_score = number_in(j, "crease_min_score", v.crease_min_score, -1000.0, 1000.0);
    v.ridge_min_score = number_in(j, "ridge_min_score", v.ridge_min_score, -1000.0, 1000.0);
    v.hachure_spacing_min = number_in(j, "hachure_spacing_min", v.hachure_spacing_min, 0.5, 1000.0);
    v.hachure_spacing_max = number_in(j, "hachure_spacing_max", v.hachure_spacing_max, v.hachure_spacing_min, 1000.0);
    if (j.contains("style")) {
        const json& s = j.at("style");
        if (!s.is_string() || s.get<std::string>().empty() || s.get<std::string>().size() > 4096)
            throw std::invalid_argument("style must be a style name or file");
        v.style = s.get<std::string>();
    }
    if (j.contains("layers")) {
        const json& layers = j.at("layers");
        if (!layers.is_object()) throw std::invalid_argument("layers must be an object of layer names");
        for (const auto& [name, on] : layers.items()) {
            bool known = false;
            for (LayerKind k : all_layers) known = known || layer_name(k) == name;
            if (!known) throw std::invalid_argument("unknown layer \"" + name.substr(0, 40) + "\"");
            if (!on.is_boolean()) throw std::invalid_argument("layer " + name + " must be true or false");
            v.visible[name] = on.get<bool>();
        }
    }
    return v;
}

std::map<std::string, bool> scene_visibility(const std::string& base) {
    std::map<std::string, bool> visible;
    const toml::value root = parse_toml_text("scene", "", base);
    if (!root.is_table() || !root.contains("style") || !root.at("style").is_table()) return visible;
    for (const auto& [name, t] : root.at("style").as_table())
        if (t.is_table() && t.as_table().count("visible") && t.as_table().at("visible").is_boolean())
            visible[name] = t.as_table().at("visible").as_boolean();
    return visible;
}

std::string with_cache_dir(const std::string& base, const std::string& dir) {
    const toml::value parsed = parse_toml_text("scene", "", base);
    toml::table root = parsed.is_table() ? parsed.as_table() : toml::table{};
    table_at(root, "cache")["dir"] = dir;
    std::ostringstream o;
    write_table(o, "", root);
    return o.str();
}

std::string scene_text(const std::string& base, const std::string& dem, const PreviewView& v) {
    const toml::value parsed = parse_toml_text("scene", "", base);
    toml::table root = parsed.is_table() ? parsed.as_table() : toml::table{};
    toml::table& terrain = table_at(root, "terrain");
    terrain["dem"] = dem;
    terrain["vertical_exaggeration"] = v.vertical_exaggeration;
    if (v.sea_level) terrain["sea_level"] = *v.sea_level;
    else terrain.erase("sea_level");
    toml::table& camera = table_at(root, "camera");
    camera.erase("position"), camera.erase("elevation"), camera.erase("distance");
    camera["projection"] = v.orthographic ? "orthographic" : "perspective";
    camera["target"] = toml_number(v.target_x) + " " + toml_number(v.target_y);
    if (!v.orthographic) camera["distance"] = v.distance;
    camera["azimuth"] = v.azimuth, camera["altitude"] = v.altitude, camera["fov"] = v.fov;
    camera["width"] = v.width, camera["height"] = v.height;
    if (v.map_scale > 0.0) table_at(root, "map")["scale"] = v.map_scale;
    else root.erase("map");
    toml::table& light = table_at(root, "light");
    light["azimuth"] = v.light_azimuth, light["altitude"] = v.light_altitude;
    table_at(root, "creases")["min_score"] = v.crease_min_score;
    table_at(root, "ridges")["min_score"] = v.ridge_min_score;
    toml::table& hachures = table_at(root, "hachures");
    hachures["spacing_min_px"] = v.hachure_spacing_min, hachures["spacing_max_px"] = v.hachure_spacing_max;
    toml::table& style = table_at(root, "style");
    style["name"] = v.style;
    for (const auto& [name, on] : v.visible) {
        if (!on) table_at(style, name)["visible"] = false;
        else if (style.count(name) && style.at(name).is_table()) style.at(name).as_table().erase("visible");
    }
    root["seed"] = toml::integer(v.seed);
    std::ostringstream o;
    o << "# penink scene saved by `penink preview`: `penink render` of this file draws the view shown.\n";
    write_table(o, "", root);
    return o.str();
}

}  // namespace penink
