// Atomic file output: content goes to `PATH.tmp-XXXXXX` in the target's directory and is
// renamed onto PATH only when complete; on any failure the temp file is removed, so no
// partial output is ever left. Errors: Error("export", path, "cannot write file (REASON)").
#pragma once
#include <functional>
#include <string>
#include <string_view>

namespace penink {

// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Creates the temp file, calls write(temp_path) (which may reopen and overwrite it, e.g. an
// image library), then renames it onto `path`. Exceptions from `write` remove the temp file
// and propagate unchanged.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace penink
