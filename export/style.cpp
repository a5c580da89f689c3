// Colours and the shipped styles (technical, field-sketch); styles/*.toml mirror these values.
#include "export/style.hpp"

#include <stdexcept>

#include "core/error.hpp"

namespace penink {

namespace {

int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

void set_width(LayerStyle& s, double near, double far) {
    s.width = near;
    s.width_far = far;
}

void set_taper(LayerStyle& s, double taper, double taper_min, double weight_min, double weight_max) {
    s.taper = taper, s.taper_min = taper_min;
    s.weight_min = weight_min, s.weight_max = weight_max;
}

}  // namespace

Rgb parse_rgb(const std::string& text) {
    const bool short_form = text.size() == 4;
    if (text.empty() || text[0] != '#' || (text.size() != 7 && !short_form))
        throw std::invalid_argument("must be \"#rrggbb\"");
    int v[6];
    for (size_t i = 1; i < text.size(); ++i) {
        v[i - 1] = hex_digit(text[i]);
        if (v[i - 1] < 0) throw std::invalid_argument("must be \"#rrggbb\"");
    }
    if (short_form)
        return Rgb{static_cast<std::uint8_t>(v[0] * 17), static_cast<std::uint8_t>(v[1] * 17),
                   static_cast<std::uint8_t>(v[2] * 17)};
    return Rgb{static_cast<std::uint8_t>(v[0] * 16 + v[1]),
               static_cast<std::uint8_t>(v[2] * 16 + v[3]),
               static_cast<std::uint8_t>(v[4] * 16 + v[5])};
}

std::string rgb_hex(Rgb c) {
    static constexpr char digits[] = "0123456789abcdef";
    std::string s = "#";
    for (std::uint8_t v : {c.r, c.g, c.b}) {
        s += digits[v >> 4];
        s += digits[v & 15];
    }
    return s;
}

Style default_style() {
    Style s;
    s.name = "technical";
    for (LayerStyle& l : s.layers) l = LayerStyle{};
    set_width(s.layer(LayerKind::surface), 0.5, 0.5);
    set_width(s.layer(LayerKind::coastline), 0.8, 0.8);  // the shore: a heavier blue-black line
    s.layer(LayerKind::coastline).color = Rgb{0x10, 0x20, 0x40};
    set_width(s.layer(LayerKind::hachures), 1.0, 1.0);  // tone: spacing follows it (lines/hachures.hpp)
    set_width(s.layer(LayerKind::ridges), 0.6, 0.6);
    set_width(s.layer(LayerKind::creases), 0.6, 0.6);
    set_width(s.layer(LayerKind::pels), 0.5, 0.5);
    set_width(s.layer(LayerKind::textures), 0.4, 0.4);
    set_width(s.layer(LayerKind::feature_edges), 0.8, 0.8);
    set_width(s.layer(LayerKind::silhouettes), 1.2, 1.2);
    // silhouette fragments of small bumps read as dashes: drawn from 8 px on
    s.layer(LayerKind::silhouettes).min_length = 8.0;
    // the hierarchy of weight: tapered creases and ridges, trunks heavier than twigs, profile
    // lines heavier than folds (styles/README.md)
    // tone by width and spacing: thin sparse strokes in the light tones, heavy close ones in the
    // dark (the pen's width on a curve of the tone, lines/hachures.hpp); a short lift so that
    // short strokes keep their ink
    set_taper(s.layer(LayerKind::hachures), 2.0, 0.4, 0.55, 2.2);
    set_taper(s.layer(LayerKind::ridges), 6.0, 0.15, 0.35, 1.65);
    set_taper(s.layer(LayerKind::creases), 6.0, 0.15, 0.5, 1.75);
    set_taper(s.layer(LayerKind::silhouettes), 8.0, 0.3, 0.4, 1.25);
    // map furniture (lines/map_furniture.hpp): a heavy neatline, fine ticks, labels in points
    const struct { LayerKind k; double w, pt; } furniture[] = {
        {LayerKind::neatline, 1.5, 0.0}, {LayerKind::grid, 0.5, 6.0}, {LayerKind::scale_bar, 0.8, 7.0},
        {LayerKind::north_arrow, 0.8, 9.0}, {LayerKind::title, 0.8, 14.0}};
    for (const auto& row : furniture) {
        set_width(s.layer(row.k), row.w, row.w);
        s.layer(row.k).font_size = row.pt;
        s.layer(row.k).min_length = 0.0;  // a tick is short
    }
    return s;
}

namespace {

Style field_sketch_style() {
    Style s = default_style();
    s.name = "field-sketch";
    s.background = Rgb{0xfb, 0xf8, 0xf0};
    s.fill = s.background;
    const struct { LayerKind k; double w, wf, keep; } table[] = {
        {LayerKind::surface, 0.8, 0.4, 1.0},        {LayerKind::coastline, 1.2, 0.5, 1.0},
        {LayerKind::hachures, 1.0, 1.0, 1.0},       {LayerKind::ridges, 1.1, 0.4, 0.5},
        {LayerKind::creases, 1.0, 0.35, 0.5},       {LayerKind::pels, 0.8, 0.3, 0.4},
        {LayerKind::textures, 0.6, 0.25, 0.3},      {LayerKind::feature_edges, 1.4, 0.6, 0.8},
        {LayerKind::silhouettes, 1.8, 0.7, 1.0}};
    for (const auto& row : table) {
        LayerStyle& l = s.layer(row.k);
        l.color = Rgb{0x2b, 0x24, 0x1e};
        set_width(l, row.w, row.wf);
        l.opacity = 0.95;
        l.opacity_far = 0.55;
        l.keep_far = row.keep;
        l.sketch = 1.5;
        l.overshoot = 2.0;
    }
    s.layer(LayerKind::coastline).color = Rgb{0x1e, 0x2a, 0x3a};  // blue-black ink
    s.layer(LayerKind::silhouettes).repeat = 2;
    s.layer(LayerKind::textures).dash = {6.0, 3.0};
    set_taper(s.layer(LayerKind::hachures), 2.5, 0.3, 0.55, 2.2);
    set_taper(s.layer(LayerKind::ridges), 8.0, 0.1, 0.35, 1.65);
    set_taper(s.layer(LayerKind::creases), 8.0, 0.1, 0.5, 1.6);
    set_taper(s.layer(LayerKind::silhouettes), 10.0, 0.25, 0.45, 1.3);
    // tone by spacing: one width at every depth (the hachures' own spacing and contrast fall
    // with distance), a light wobble and no overshoot into the creases they yield to
    s.layer(LayerKind::hachures).sketch = 0.5;
    s.layer(LayerKind::hachures).overshoot = 0.0;
    for (LayerKind k : all_layers)
        if (is_furniture(k)) s.layer(k).color = Rgb{0x2b, 0x24, 0x1e};  // the ink, without the sketch
    return s;
}

// For pen plotters (styles/plotter.toml): one pen colour per layer, pen widths in millimetres
// whatever the page, no surface mask, no sketch or width bands.
Style plotter_style() {
    Style s = default_style();
    s.name = "plotter";
    s.no_fill = true;
    s.widths_mm = true;
    s.bands = 1;
    const struct { LayerKind k; Rgb c; double w; } table[] = {
        {LayerKind::surface, {0x80, 0x80, 0x80}, 0.3},      {LayerKind::coastline, {0x00, 0x30, 0x60}, 0.4},
        {LayerKind::hachures, {0x40, 0x40, 0x40}, 0.3},    {LayerKind::ridges, {0xb0, 0x30, 0x20}, 0.3},
        {LayerKind::creases, {0x20, 0x50, 0xb0}, 0.3},      {LayerKind::pels, {0x20, 0x80, 0x40}, 0.3},
        {LayerKind::textures, {0x90, 0x60, 0x20}, 0.25},    {LayerKind::feature_edges, {0x60, 0x20, 0x80}, 0.5},
        {LayerKind::silhouettes, {0x00, 0x00, 0x00}, 0.5}};
    for (const auto& row : table) {
        LayerStyle& l = s.layer(row.k);
        l.color = row.c;
        set_width(l, row.w, row.w);
        set_taper(l, 0.0, 0.0, 1.0, 1.0);  // single centre-line strokes, one pen width
    }
    // map furniture in black: its lines in millimetres, and no text (a pen does not set type)
    for (LayerKind k : all_layers)
        if (is_furniture(k)) {
            set_width(s.layer(k), k == LayerKind::neatline ? 0.5 : 0.3, k == LayerKind::neatline ? 0.5 : 0.3);
            s.layer(k).font_size = 0.0;
        }
    return s;
}

}  // namespace

std::vector<std::string> builtin_style_names() { return {"technical", "field-sketch", "plotter"}; }

Style builtin_style(const std::string& name) {
    if (name == "technical") return default_style();
    if (name == "field-sketch") return field_sketch_style();
    if (name == "plotter") return plotter_style();
    throw Error("style", name, "unknown style \"" + name + "\" (use technical, field-sketch or plotter)");
}

Style resolve_style(const std::string& name_or_path) {
    for (const std::string& n : builtin_style_names())
        if (n == name_or_path) return builtin_style(n);
    return load_style(name_or_path);
}

}  // namespace penink
