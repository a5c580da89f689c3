// Atomic file output: content goes to `PATH.tmp-XXXXXX` in the target's directory and is
// renamed onto PATH only when complete; on any failure the temp file is removed, so no
// partial output is ever left. Errors: Error("export", path, "cannot write file (REASON)").
#pragma once
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace penink {

// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Writes several files together: bytes_of(i) gives the content of paths[i]; each goes to a temp
// file beside its path as it comes, and only when every one is written are they renamed onto
// their paths. On any failure (an exception from bytes_of, a write) every temp file is removed
// and no path is touched; the exception propagates.
void write_files_together(const std::vector<std::string>& paths,
                          const std::function<std::string(std::size_t)>& bytes_of);

}  // namespace penink
