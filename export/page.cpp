// Page sizes, layout and number formatting for the writers (page.hpp).
#include "export/page.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.hpp"

namespace penink {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool parse_custom(const std::string& s, double& w, double& h) {
    const size_t x = s.find('x');
    if (x == std::string::npos || s.size() < 3 || s.substr(s.size() - 2) != "mm") return false;
    const char* b = s.data();
    auto r1 = std::from_chars(b, b + x, w);
    auto r2 = std::from_chars(b + x + 1, b + s.size() - 2, h);
    return r1.ec == std::errc() && r1.ptr == b + x && r2.ec == std::errc() &&
           r2.ptr == b + s.size() - 2 && w > 0 && h > 0;
}

}  // namespace

void page_size_mm(const std::string& page, double& w_mm, double& h_mm) {
    const std::string p = lower(page);
    static constexpr struct { const char* name; double w, h; } sizes[] = {
        {"a0", 841, 1189}, {"a1", 594, 841}, {"a2", 420, 594}, {"a3", 297, 420},
        {"a4", 210, 297},  {"a5", 148, 210}, {"a6", 105, 148}, {"b4", 250, 353},
        {"b5", 176, 250},  {"letter", 215.9, 279.4}, {"legal", 215.9, 355.6},
        {"tabloid", 279.4, 431.8}};
    for (const auto& s : sizes)
        if (p == s.name) {
            w_mm = s.w;
            h_mm = s.h;
            return;
        }
    if (!parse_custom(p, w_mm, h_mm))
        throw std::invalid_argument("unknown page size \"" + page +
                                    "\" (use A0-A6, B4, B5, letter, legal, tabloid or WxHmm)");
    if (w_mm > max_page_mm || h_mm > max_page_mm)
        throw std::invalid_argument("page \"" + page + "\" is too large (at most 5000 mm a side)");
}

PageLayout page_layout(int width, int height, const PageOptions& o, const std::string& path) {
    if (!(o.dpi > 0.0) || !std::isfinite(o.dpi)) throw Error("export", path, "dpi must be > 0");
    if (width <= 0 || height <= 0) throw Error("export", path, "drawing has no size");
    PageLayout L;
    if (o.page.empty()) {
        L.scale_mm = mm_per_inch / o.dpi;
        L.page_w_mm = width * L.scale_mm + 2 * o.margin_mm;
        L.page_h_mm = height * L.scale_mm + 2 * o.margin_mm;
        L.offset_x_mm = L.offset_y_mm = o.margin_mm;
        return L;
    }
    try {
        page_size_mm(o.page, L.page_w_mm, L.page_h_mm);
    } catch (const std::invalid_argument& e) {
        throw Error("export", path, e.what());
    }
    const bool custom = lower(o.page).find('x') != std::string::npos;
    if (!custom && (width > height) != (L.page_w_mm > L.page_h_mm)) std::swap(L.page_w_mm, L.page_h_mm);
    const double aw = L.page_w_mm - 2 * o.margin_mm, ah = L.page_h_mm - 2 * o.margin_mm;
    if (aw <= 0 || ah <= 0) throw Error("export", path, "margin leaves no room on the page");
    L.scale_mm = std::min(aw / width, ah / height);
    L.offset_x_mm = 0.5 * (L.page_w_mm - width * L.scale_mm);
    L.offset_y_mm = 0.5 * (L.page_h_mm - height * L.scale_mm);
    return L;
}

namespace {

// append_number's text for |value| < 1e14 and 0..4 decimals without std::to_chars (whose
// arbitrary-precision path costs ~500 instructions a number; an SVG frame writes ~10^5 of them):
// value * 10^decimals is exact in x87 long double (53 significant bits times at most 10 for
// 10^4 = 2^4 * 625 fit its 64), and rounding it to the nearest integer, ties to even, is the
// rounding to_chars' fixed format makes of the exact binary value. Then the same trimming.
bool append_number_exactly(std::string& out, double value, int decimals) {
    static_assert(std::numeric_limits<long double>::digits >= 64, "x87 extended precision");
    if (decimals < 0 || decimals > 4 || !(std::fabs(value) < 1e14)) return false;
    static constexpr long double scale[] = {1.0L, 10.0L, 100.0L, 1000.0L, 10000.0L};
    const long long q = std::llrintl(static_cast<long double>(value) * scale[decimals]);  // |q| < 1e18
    if (q == 0) {  // "0", "-0" and "-0.00" all read "0"
        out += '0';
        return true;
    }
    unsigned long long a = q < 0 ? 0ull - static_cast<unsigned long long>(q) : static_cast<unsigned long long>(q);
    char buf[32];
    char* end = buf + sizeof buf;
    char* p = end;
    int frac = decimals;
    while (frac > 0 && a % 10 == 0) a /= 10, --frac;  // trailing zeros of the fraction dropped
    for (int k = 0; k < frac; ++k) *--p = char('0' + a % 10), a /= 10;
    if (frac > 0) *--p = '.';
    do *--p = char('0' + a % 10), a /= 10;
    while (a > 0);
    if (q < 0) *--p = '-';
    out.append(p, end);
    return true;
}

}  // namespace

void append_number(std::string& out, double value, int decimals) {
    char buf[512];  // the largest double has 309 digits before the point
    if (!std::isfinite(value)) value = 0.0;
    if (append_number_exactly(out, value, decimals)) return;
    auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
    char* end = r.ptr;
    if (decimals > 0) {
        while (end > buf && end[-1] == '0') --end;
        if (end > buf && end[-1] == '.') --end;
    }
    if (end - buf == 2 && buf[0] == '-' && buf[1] == '0') {
        out += '0';
        return;
    }
    out.append(buf, end);
}

std::string format_number(double value, int decimals) {
    std::string s;
    append_number(s, value, decimals);
    return s;
}

std::map<std::string, std::string> merged_metadata(const std::map<std::string, std::string>& a,
                                                   const std::map<std::string, std::string>& b) {
    std::map<std::string, std::string> m = a;
    for (const auto& [k, v] : b) m[k] = v;
    return m;
}

std::string drawing_title(const std::map<std::string, std::string>& metadata, const std::string& path) {
    const auto it = metadata.find("title");
    if (it != metadata.end() && !it->second.empty()) return it->second;
    return path.substr(path.find_last_of('/') + 1);
}

std::string drawing_description(const std::map<std::string, std::string>& metadata) {
    const auto it = metadata.find("description");
    return it == metadata.end() ? std::string() : it->second;
}

}  // namespace penink
