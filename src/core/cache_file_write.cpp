// Writing a cache file whole (cache_file_write.hpp).
#include "core/cache_file_write.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>

namespace penink {

int write_cache_file(const std::string& path, const std::vector<std::span<const std::uint8_t>>& parts) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    std::FILE* out = std::fopen(tmp.c_str(), "wb");
    if (!out) return errno ? errno : EIO;
    int err = 0;
    for (const std::span<const std::uint8_t>& p : parts)
        if (!err && !p.empty() && std::fwrite(p.data(), 1, p.size(), out) != p.size()) err = errno ? errno : EIO;
    if (std::fclose(out) != 0 && !err) err = errno ? errno : EIO;
    std::error_code ec;
    if (!err) {
        std::filesystem::rename(tmp, path, ec);
        if (ec) err = ec.value();
    }
    if (err) std::filesystem::remove(tmp, ec);
    return err;
}

}  // namespace penink
