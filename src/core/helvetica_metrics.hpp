// Text in the PDF standard font Helvetica (map furniture labels, export writers): UTF-8 turned into
// the single bytes of PDF's WinAnsiEncoding as far as Latin-1 reaches (printable ASCII and
// U+00A0..U+00FF; anything else becomes '?'), and the advance width of such text, in ems, from
// Helvetica's glyph widths (thousandths of an em; URW's Nimbus Sans, metric-compatible with
// Helvetica: /usr/share/fonts/type1/urw-base35/NimbusSans-Regular.afm on Debian's fonts-urw-base35).
#pragma once
#include <string>
#include <string_view>

namespace penink {

// Bytes 32..126 and 160..255 (WinAnsi = Latin-1 there); control characters, malformed UTF-8 and
// characters outside Latin-1 become '?', line breaks and tabs a space.
std::string latin1_text(std::string_view utf8);

// Advance width of latin1_text(utf8) set in Helvetica at 1 em (no kerning).
double helvetica_advance_em(std::string_view utf8);

}  // namespace penink
