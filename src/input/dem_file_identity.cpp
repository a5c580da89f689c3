// A DEM file's identity from its and its side files' status (dem_file_identity.hpp).
#include "input/dem_file_identity.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "core/hash64.hpp"
#include "input/dem_side_files.hpp"

namespace penink {

namespace {

// The status fields that change with the file's bytes or its replacement, chained into h; a
// missing file hashes its absence.
std::uint64_t chain_status(const std::string& path, std::uint64_t h) {
    struct stat st {};
    std::uint64_t f[8] = {};
    if (::stat(path.c_str(), &st) == 0) {
        f[0] = 1, f[1] = std::uint64_t(st.st_dev), f[2] = std::uint64_t(st.st_ino), f[3] = std::uint64_t(st.st_size);
        f[4] = std::uint64_t(st.st_mtim.tv_sec), f[5] = std::uint64_t(st.st_mtim.tv_nsec);
        f[6] = std::uint64_t(st.st_ctim.tv_sec), f[7] = std::uint64_t(st.st_ctim.tv_nsec);
    }
    return hash64(f, sizeof f, h);
}

}  // namespace

std::uint64_t dem_file_identity(const std::string& dem_path) {
    struct stat st {};
    if (::stat(dem_path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return 0;
    const std::string absolute = std::filesystem::absolute(dem_path).lexically_normal().string();
    std::uint64_t h = hash64(absolute.data(), absolute.size());
    h = chain_status(dem_path, h);
    for (const std::string& side : dem_side_files(dem_path)) h = chain_status(side, h);
    return h == 0 ? 1 : h;
}

}  // namespace penink
