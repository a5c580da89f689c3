// Reading styles from TOML (toml11 3.7): a root of top-level keys plus one table per layer
// (or "all", applied first). Unknown keys and out-of-range values are errors (styles/README.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "core/closest_name.hpp"
#include "core/error.hpp"
#include "core/toml_file.hpp"
#include "export/style.hpp"

namespace penink {

namespace {

// A bad key or value; turned into penink::Error with the file name by the caller.
struct StyleProblem : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string where(const std::string& table) { return table.empty() ? "" : " (in [" + table + "])"; }

double number(const toml::value& v, const std::string& key, const std::string& table) {
    if (v.is_floating()) return v.as_floating();
    if (v.is_integer()) return static_cast<double>(v.as_integer());
    throw StyleProblem(key + " must be a number" + where(table));
}

double number_at_least(const toml::value& v, const std::string& key, const std::string& table,
                       double lo) {
    const double x = number(v, key, table);
    if (!std::isfinite(x) || x < lo)
        throw StyleProblem(key + " must be >= " + (lo == 0 ? "0" : "1") + where(table));
    return x;
}

double unit_number(const toml::value& v, const std::string& key, const std::string& table) {
    const double x = number(v, key, table);
    if (!(x >= 0.0 && x <= 1.0)) throw StyleProblem(key + " must be in [0, 1]" + where(table));
    return x;
}

Rgb colour(const toml::value& v, const std::string& key, const std::string& table) {
    if (!v.is_string()) throw StyleProblem(key + " must be a string \"#rrggbb\"" + where(table));
    try {
        return parse_rgb(v.as_string().str);
    } catch (const std::invalid_argument&) {
        throw StyleProblem(key + " must be \"#rrggbb\" (got \"" + v.as_string().str + "\")" +
                           where(table));
    }
}

std::vector<double> dash_array(const toml::value& v, const std::string& table) {
    if (!v.is_array()) throw StyleProblem("dash must be an array of numbers" + where(table));
    if (v.as_array().size() > max_dash_entries)
        throw StyleProblem("dash must have at most " + std::to_string(max_dash_entries) + " numbers" + where(table));
    std::vector<double> dash;
    double sum = 0.0;
    for (const toml::value& x : v.as_array()) {
        dash.push_back(number_at_least(x, "dash", table, 0.0));
        if (dash.back() > 0.0 && dash.back() < min_dash_px)
            throw StyleProblem("dash lengths must be 0 or at least 0.1 px (got " + message_number(dash.back()) + ")" +
                               where(table));
        sum += dash.back();
    }
    if (!dash.empty() && sum <= 0.0) throw StyleProblem("dash must not be all zeros" + where(table));
    if (!dash.empty() && sum < min_dash_pattern_px)
        throw StyleProblem("dash pattern must add up to at least 1 px (got " + message_number(sum) + ")" + where(table));
    return dash;
}

// The keys a layer table, the root and the layer tables take (for suggestions).
std::vector<std::string> layer_keys() {
    return {"color", "colour", "width", "width_far", "opacity", "opacity_far", "keep_far",
            "dash", "sketch", "overshoot", "min_length", "repeat", "visible", "taper", "taper_min",
            "weight_min", "weight_max", "font_size"};
}
std::vector<std::string> root_keys() { return {"name", "fill", "background", "near", "far", "bands", "width_unit"}; }
std::vector<std::string> layer_names() {
    std::vector<std::string> names = {"all"};
    for (LayerKind k : all_layers) names.emplace_back(layer_name(k));
    return names;
}

std::vector<std::string> sorted_keys(const toml::value& t) {
    std::vector<std::string> keys;
    for (const auto& [k, v] : t.as_table()) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    return keys;
}

void apply_layer_key(LayerStyle& l, const std::string& key, const toml::value& v,
                     const std::string& table) {
    if (key == "color" || key == "colour") l.color = colour(v, key, table);
    else if (key == "width") l.width = number_at_least(v, key, table, 0.0);
    else if (key == "width_far") l.width_far = number_at_least(v, key, table, 0.0);
    else if (key == "opacity") l.opacity = unit_number(v, key, table);
    else if (key == "opacity_far") l.opacity_far = unit_number(v, key, table);
    else if (key == "keep_far") l.keep_far = unit_number(v, key, table);
    else if (key == "dash") l.dash = dash_array(v, table);
    else if (key == "sketch") l.sketch = number_at_least(v, key, table, 0.0);
    else if (key == "overshoot") l.overshoot = number_at_least(v, key, table, 0.0);
    else if (key == "min_length") l.min_length = number_at_least(v, key, table, 0.0);
    else if (key == "taper") l.taper = number_at_least(v, key, table, 0.0);
    else if (key == "taper_min") l.taper_min = unit_number(v, key, table);
    else if (key == "weight_min") l.weight_min = number_at_least(v, key, table, 0.0);
    else if (key == "weight_max") l.weight_max = number_at_least(v, key, table, 0.0);
    else if (key == "font_size") {
        l.font_size = number_at_least(v, key, table, 0.0);
        if (l.font_size > 1000.0) throw StyleProblem("font_size must be at most 1000 (points)" + where(table));
    }
    else if (key == "repeat") {
        if (!v.is_integer() || v.as_integer() < 1 || v.as_integer() > 16)
            throw StyleProblem("repeat must be an integer in [1, 16]" + where(table));
        l.repeat = static_cast<int>(v.as_integer());
    } else if (key == "visible") {
        if (!v.is_boolean()) throw StyleProblem("visible must be true or false" + where(table));
        l.visible = v.as_boolean();
    } else {
        throw StyleProblem("unknown key \"" + key + "\"" + where(table) + did_you_mean(key, layer_keys()));
    }
}

// A table's keys on one layer; `width` / `opacity` alone also set the far value (uniform).
void apply_layer_table(LayerStyle& l, const toml::value& t, const std::string& table) {
    const std::vector<std::string> keys = sorted_keys(t);
    const auto has = [&](const char* k) { return std::find(keys.begin(), keys.end(), k) != keys.end(); };
    for (const std::string& k : keys) apply_layer_key(l, k, t.as_table().at(k), table);
    if (has("width") && !has("width_far")) l.width_far = l.width;
    if (has("opacity") && !has("opacity_far")) l.opacity_far = l.opacity;
}

bool find_layer(const std::string& name, LayerKind& out) {
    for (LayerKind k : all_layers)
        if (layer_name(k) == name) {
            out = k;
            return true;
        }
    return false;
}

void apply_root_key(Style& s, const std::string& key, const toml::value& v) {
    if (key == "name") {
        if (!v.is_string()) throw StyleProblem("name must be a string");
        s.name = v.as_string().str;
    } else if (key == "fill") {
        s.no_fill = v.is_string() && v.as_string().str == "none";
        if (!s.no_fill) s.fill = colour(v, key, "");
    } else if (key == "width_unit") {
        if (!v.is_string() || (v.as_string().str != "px" && v.as_string().str != "mm"))
            throw StyleProblem("width_unit must be \"px\" (image pixels) or \"mm\" (on the page)");
        s.widths_mm = v.as_string().str == "mm";
    } else if (key == "background") s.background = colour(v, key, "");
    else if (key == "near") s.near = unit_number(v, key, "");
    else if (key == "far") s.far = unit_number(v, key, "");
    else if (key == "bands") {
        if (!v.is_integer() || v.as_integer() < 1 || v.as_integer() > 16)
            throw StyleProblem("bands must be an integer in [1, 16]");
        s.bands = static_cast<int>(v.as_integer());
    } else throw StyleProblem("unknown key \"" + key + "\"" + did_you_mean(key, root_keys()));
}

void apply_table(Style& s, const toml::value& table) {
    if (!table.is_table()) throw StyleProblem("style must be a table");
    const std::vector<std::string> keys = sorted_keys(table);
    for (const std::string& k : keys) {  // scalars first, then "all", then the layers
        const toml::value& v = table.as_table().at(k);
        if (!v.is_table()) apply_root_key(s, k, v);
    }
    if (table.contains("all") && table.at("all").is_table())
        for (LayerKind k : all_layers)
            if (!is_furniture(k)) apply_layer_table(s.layer(k), table.at("all"), "all");
    for (const std::string& k : keys) {
        const toml::value& v = table.as_table().at(k);
        LayerKind kind;
        if (!v.is_table() || k == "all") continue;
        if (!find_layer(k, kind)) throw StyleProblem("unknown layer \"" + k + "\"" + did_you_mean(k, layer_names()));
        apply_layer_table(s.layer(kind), v, k);
    }
    if (!(s.near < s.far)) throw StyleProblem("near must be less than far");
}

}  // namespace

namespace {

// The table over `style`, whole or not at all.
void apply_style_table(Style& style, const toml::value& table, const std::string& source) {
    Style s = style;
    try {
        apply_table(s, table);
    } catch (const StyleProblem& e) {
        throw Error("style", source, e.what());
    }
    style = s;
}

}  // namespace

void apply_style_overrides(Style& style, const std::string& toml_text, const std::string& source) {
    apply_style_table(style, parse_toml_text("style", source, toml_text), source);
}

Style load_style(const std::string& path) {
    const toml::value root = read_toml_file("style", path, "style file");
    Style s = default_style();
    s.name.clear();
    apply_style_table(s, root, path);
    if (s.name.empty()) {
        const size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
        const size_t from = slash == std::string::npos ? 0 : slash + 1;
        s.name = path.substr(from, dot == std::string::npos || dot < from ? std::string::npos : dot - from);
    }
    return s;
}

}  // namespace penink
