// A TOML input file (a scene or a style) read and parsed with the checks every such file gets:
// a regular local file under max_text_input_bytes (core/input_files.hpp's read_input_text), its
// nesting bounded before the parser sees it (check_toml_nesting), UTF-8 (toml11 3.7 reads past its
// buffer reporting some sequences that are not), then toml11's parse. Only the readers of TOML
// (scene/scene_file.cpp, export/style_parse.cpp, preview/preview_view.cpp and the preview session)
// include it: no other header carries toml11's types.
#pragma once
#include <string>

#include <toml.hpp>

namespace penink {

// Throws penink::Error(stage, path, "invalid TOML: <reason>") with the parser's first line, or the
// reading checks' own errors. `what` names the file in those ("scene file", "style file").
toml::value read_toml_file(const std::string& stage, const std::string& path, const std::string& what);

// The same checks and parse of TOML text already read (`path` names it in errors).
toml::value parse_toml_text(const std::string& stage, const std::string& path, const std::string& text);

}  // namespace penink
