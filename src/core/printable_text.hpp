// Text from an input file made safe to show in a one-line message: bytes that are not valid
// UTF-8, and control characters, written as \xNN (a backslash as \\), well-formed UTF-8 kept,
// and the text cut after max_chars characters with "...".
#pragma once
#include <cstddef>
#include <string>

namespace penink {

std::string printable_text(const std::string& text, std::size_t max_chars = 60);

// Offset of the first byte of `text` that does not start a well-formed UTF-8 sequence (ASCII
// included), npos when there is none.
std::size_t invalid_utf8_at(const std::string& text);
inline constexpr std::size_t npos_utf8 = std::size_t(-1);

}  // namespace penink
