// Writing a cache file whole (cache_file_write.hpp).
#include "core/cache_file_write.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>

namespace penink {

int write_cache_file(const std::string& path, const std::vector<std::span<const std::uint8_t>>& parts) {
    CacheFileStream out(path);
    for (const std::span<const std::uint8_t>& p : parts) out.append(p);
    return out.finish();
}

CacheFileStream::CacheFileStream(const std::string& path)
    : path_(path), tmp_(path + ".tmp-" + std::to_string(::getpid())), out_(std::fopen(tmp_.c_str(), "wb")) {
    if (!out_) err_ = errno ? errno : EIO, done_ = true;
}

CacheFileStream::~CacheFileStream() {
    if (done_) return;
    std::fclose(out_);
    std::error_code ec;
    std::filesystem::remove(tmp_, ec);
}

int CacheFileStream::append(std::span<const std::uint8_t> p) {
    if (!err_ && !p.empty() && std::fwrite(p.data(), 1, p.size(), out_) != p.size()) err_ = errno ? errno : EIO;
    return err_;
}

int CacheFileStream::finish(std::span<const std::uint8_t> head) {
    if (done_) return err_;  // never opened
    done_ = true;
    if (!err_ && !head.empty() &&
        (std::fseek(out_, 0, SEEK_SET) != 0 || std::fwrite(head.data(), 1, head.size(), out_) != head.size()))
        err_ = errno ? errno : EIO;
    if (std::fclose(out_) != 0 && !err_) err_ = errno ? errno : EIO;
    std::error_code ec;
    if (!err_) {
        std::filesystem::rename(tmp_, path_, ec);
        if (ec) err_ = ec.value();
    }
    if (err_) std::filesystem::remove(tmp_, ec);
    return err_;
}

}  // namespace penink
