// Atomic file output, all or none: content goes to a temporary `PATH.penink-PID.tmp-XXXXXX` in the
// target's directory, is flushed to the disk (fsync), and is renamed onto PATH only when every
// file of the set is complete. While a set is placed, each earlier file is kept as a hard link
// `PATH.penink-PID.old` until every new file is in; a failure to place any of them puts the old
// files back (and removes new files that had no old one), so a failed command leaves the set as
// it was. Temporaries and kept old files carry the writing process's id: the next write beside
// a path removes those of processes that no longer run (an old file whose path is missing is put
// back: the run was killed between its two renames). Errors: Error("export", path, "cannot write
// file (REASON)"); a short write, ENOSPC, EIO, EFBIG are errors like any other.
#pragma once
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace penink {

// Writes `bytes` to `path` atomically.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Writes several files together: bytes_of(i) gives the content of paths[i]; each goes to a temp
// file beside its path as it comes, and only when every one is written and flushed are they
// placed onto their paths. On any failure (an exception from bytes_of, a write, a rename) every
// temp file is removed and every path holds what it held before; the exception propagates.
void write_files_together(const std::vector<std::string>& paths,
                          const std::function<std::string(std::size_t)>& bytes_of);

// For several paths written by libraries (GDAL): write(i, temp) writes paths[i]'s content to
// `temp` (which it may reopen and overwrite), which is then flushed; then all are placed together
// as in write_files_together. Exceptions from `write` remove the temporaries and propagate.
void write_atomically_together(const std::vector<std::string>& paths,
                               const std::function<void(std::size_t, const std::string&)>& write);

// Removes the temporaries and kept old files beside `path` that belong to processes no longer
// running (the write functions above call it; exposed for tests).
void remove_stale_temporaries(const std::string& path);

}  // namespace penink
