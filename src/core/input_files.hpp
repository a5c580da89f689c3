// Input files checked before they are opened, and outputs checked against them.
//
// Every file penink reads from a user (DEM, scene, style, flight path, mesh) is a local regular
// file: a path holding a NUL byte, a GDAL virtual or network path (any "/vs..." prefix, a
// "scheme://" URL, "http:", "ftp:" ...), a folder, a FIFO, a device or a socket is refused with
// one line before anything opens it, and a text input is refused when it is larger than its cap
// (read_input_text). TOML inputs are refused when their brackets and braces nest deeper than
// max_toml_nesting (check_toml_nesting, a pre-scan outside strings and comments, so no parser
// recursion can exhaust the stack).
//
// An output never replaces an input: check_outputs_not_inputs compares every output path with
// every input (and its side files) by device and inode after resolving symlinks, so a second
// name (a symlink, a hard link, "./x") for an input is caught too.
//
// Errors: Error(stage, path, what) with `path` made printable (printable_text) when it holds
// control characters or bytes that are not UTF-8.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace penink {

inline constexpr std::uint64_t max_text_input_bytes = 16ull << 20;  // scene, style, flight path
inline constexpr int max_toml_nesting = 64;

// The path as it can be shown in a one-line message.
std::string shown_path(const std::string& path);

// Refuses a path with a NUL byte or naming a GDAL virtual or network file system:
// Error(stage, path, "path holds a NUL byte") or "... is a network or virtual path (penink reads
// local files only)".
void check_local_path(const std::string& stage, const std::string& path);

// check_local_path, then: the path names a regular file (after symlinks) no larger than
// max_bytes (0: any size). Errors "no such file", "not a regular file (a folder)" / "(a FIFO)" /
// "(a device)" / "(a socket)", "file of N bytes is larger than the M MiB a <what> may have".
void check_input_file(const std::string& stage, const std::string& path, std::uint64_t max_bytes = 0,
                      const std::string& what = "input");

// check_input_file, then the whole file; Error(stage, path, "cannot read file (REASON)").
std::string read_input_text(const std::string& stage, const std::string& path,
                            std::uint64_t max_bytes = max_text_input_bytes, const std::string& what = "input");

// Refuses TOML text whose [ and { nest deeper than `max_depth` (outside strings and comments):
// Error(stage, path, "TOML nests brackets or braces deeper than 64 levels"), or whose key (a
// table header's included) has more than `max_depth` dotted parts: "TOML key has more than 64
// dotted parts" (toml11 takes minutes over 100 000).
void check_toml_nesting(const std::string& stage, const std::string& path, const std::string& text,
                        int max_depth = max_toml_nesting);

struct NamedInput {
    std::string path;
    std::string role;  // "the DEM", "the DEM's world file", "the scene" ...
};

// Refuses any output that is the same file (device and inode, symlinks followed) as an input:
// Error(stage, output, "is <role> <input> (an output never replaces an input)"). Inputs and
// outputs that do not exist are skipped.
void check_outputs_not_inputs(const std::string& stage, const std::vector<std::string>& outputs,
                              const std::vector<NamedInput>& inputs);

}  // namespace penink
