// GLSL sources embedded at build time from shaders/*.glsl (cmake/embed_files.cmake), and
// their assembly for compilation: `#include "common.glsl"` is expanded in place with `#line`
// directives whose source-string numbers map back to file names, so a driver log line
// "0:12(3)" can be reported as "common.glsl:12".
#pragma once
#include <string>
#include <vector>

namespace penink {

struct ShaderFile {
    const char* name;    // file name, e.g. "tft.vert.glsl" (inside shaders/ for the embedded ones)
    const char* source;  // file text
};

const std::vector<ShaderFile>& embedded_shaders();

// Source text of one embedded file; throws penink::Error(stage "render") when absent.
std::string shader_text(const std::string& name);

// Assembled source: `#version` first, includes expanded, `#line L S` markers where S indexes
// `files` (files[0] = name). Used for compilation and error mapping.
struct AssembledShader {
    std::string text;
    std::vector<std::string> files;
};
AssembledShader assemble_shader(const std::string& name);
// The same for a caller-supplied file (e.g. a test's own shader): `file.source` is files[0] and
// named file.name in the markers; its `#include`s resolve against the embedded shaders.
AssembledShader assemble_shader(const ShaderFile& file);

// Rewrites a driver log, replacing "S:L(" prefixes with "file:L(" using `files`.
std::string map_log_to_files(const std::string& log, const std::vector<std::string>& files);

}  // namespace penink
