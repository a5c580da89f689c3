// A DEM file's identity as the file system gives it, without reading the file: a hash of its
// device, inode, size, modification and status-change times (nanoseconds), and of the same for
// each side file GDAL may read with it (input/dem_side_files.hpp; a side file missing counts as
// such). Any write to the DEM or a side file changes its status-change time (ctime, which no
// program can set back), a replaced file has another inode, a copy another inode or device: so
// while the identity is the same, the bytes are the ones a hash made at that identity read.
// What the caches keep beside the DEM's content hash (surface/terrain_cache.hpp): a warm render
// whose DEM has the identity the cache recorded takes the recorded hash instead of reading the
// whole DEM again (seconds for a DEM of gigabytes). 0 when the DEM cannot be stat'ed (never
// matches: the DEM is then hashed, and its error reported there).
#pragma once
#include <cstdint>
#include <string>

namespace penink {

std::uint64_t dem_file_identity(const std::string& dem_path);

}  // namespace penink
