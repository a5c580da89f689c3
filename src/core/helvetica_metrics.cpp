#include "core/helvetica_metrics.hpp"

#include <cstdint>

namespace penink {

namespace {

// Glyph widths, thousandths of an em, of the WinAnsi codes 32..126 and 160..255.
constexpr std::uint16_t ascii_widths[95] = {
    278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278,
    556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556,
    1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778,
    667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556,
    333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556,
    556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584
};
constexpr std::uint16_t latin1_widths[96] = {
    278, 333, 556, 556, 556, 556, 260, 556, 333, 737, 370, 556, 584, 333, 737, 333,
    400, 584, 333, 333, 333, 556, 537, 278, 333, 333, 365, 556, 834, 834, 834, 611,
    667, 667, 667, 667, 667, 667, 1000, 722, 667, 667, 667, 667, 278, 278, 278, 278,
    722, 722, 778, 778, 778, 778, 778, 584, 778, 722, 722, 722, 722, 667, 667, 611,
    556, 556, 556, 556, 556, 556, 889, 500, 556, 556, 556, 556, 278, 278, 278, 278,
    556, 556, 556, 556, 556, 556, 556, 584, 611, 556, 556, 556, 556, 500, 556, 500
};

}  // namespace

std::string latin1_text(std::string_view utf8) {
    std::string out;
    out.reserve(utf8.size());
    for (std::size_t i = 0; i < utf8.size();) {
        const unsigned char c = static_cast<unsigned char>(utf8[i]);
        if (c < 0x80) {
            out += c == '\n' || c == '\t' || c == '\r' ? ' ' : (c >= 32 && c < 127 ? char(c) : '?');
            ++i;
            continue;
        }
        // a two-byte sequence C2/C3 xx is U+0080..U+00FF; anything longer is outside Latin-1
        const std::size_t n = (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 1;
        bool well_formed = i + n <= utf8.size() && n > 1;
        for (std::size_t k = 1; well_formed && k < n; ++k)
            well_formed = (static_cast<unsigned char>(utf8[i + k]) >> 6) == 0x2;
        if (!well_formed) {
            out += '?';
            ++i;
            continue;
        }
        const unsigned cp = n == 2 ? ((c & 0x1Fu) << 6) | (static_cast<unsigned char>(utf8[i + 1]) & 0x3Fu) : 0x100u;
        out += cp >= 0xA0 && cp <= 0xFF ? char(cp) : '?';
        i += n;
    }
    return out;
}

double helvetica_advance_em(std::string_view utf8) {
    double units = 0.0;
    for (const char ch : latin1_text(utf8)) {
        const unsigned char c = static_cast<unsigned char>(ch);
        units += c >= 160 ? latin1_widths[c - 160] : ascii_widths[c - 32];
    }
    return units / 1000.0;
}

}  // namespace penink
