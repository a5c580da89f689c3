#include "core/toml_file.hpp"

#include <sstream>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/printable_text.hpp"

namespace penink {

namespace {
// toml11's message: its first line, without the "[error] " tag.
std::string first_line(std::string text) {
    if (text.rfind("[error] ", 0) == 0) text.erase(0, 8);
    const std::size_t nl = text.find('\n');
    return nl == std::string::npos ? text : text.substr(0, nl);
}
}  // namespace

toml::value read_toml_file(const std::string& stage, const std::string& path, const std::string& what) {
    return parse_toml_text(stage, path, read_input_text(stage, path, max_text_input_bytes, what));
}

toml::value parse_toml_text(const std::string& stage, const std::string& path, const std::string& text) {
    check_toml_nesting(stage, path, text);  // before the parser, whose recursion has no bound
    if (const std::size_t bad = invalid_utf8_at(text); bad != npos_utf8)
        throw Error(stage, path, "invalid TOML: not UTF-8 text (byte " + std::to_string(bad + 1) + ")");
    try {
        std::istringstream s(text);
        return toml::parse(s, path);
    } catch (const std::exception& e) {
        throw Error(stage, path, "invalid TOML: " + first_line(e.what()));
    }
}

}  // namespace penink
