// Writing a cache file whole (the terrain cache, the drainage lines' tile files): the parts'
// bytes, one after another, go to `PATH.tmp-PID` beside PATH, which is renamed onto PATH only
// when every byte is written and the file closed; on any failure the temporary is removed and
// PATH keeps what it held. No fsync: a cache checks itself when read (lengths, checksums), so a
// crash leaving it short costs only a rebuild. Outputs the user asked for go through
// export/atomic_file.hpp instead (flushed, placed together).
#pragma once
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace penink {

// 0 when PATH holds the parts' bytes, else the errno of the first failed call (EIO when the
// system gave none).
int write_cache_file(const std::string& path, const std::vector<std::span<const std::uint8_t>>& parts);

// The same a part at a time, for a file too large to hold: parts appended as they are made, then
// finish(head) writes `head` over the file's first bytes (a header reserved by appending as many
// zeros first, whose content follows the parts) and renames the temporary into place. The first
// failure sticks (append and finish return its errno, 0 while none); a stream dropped unfinished,
// or failed, leaves PATH as it was and no temporary.
class CacheFileStream {
public:
    explicit CacheFileStream(const std::string& path);
    ~CacheFileStream();
    CacheFileStream(const CacheFileStream&) = delete;
    CacheFileStream& operator=(const CacheFileStream&) = delete;
    int append(std::span<const std::uint8_t> bytes);
    int finish(std::span<const std::uint8_t> head = {});

private:
    std::string path_, tmp_;
    std::FILE* out_ = nullptr;
    int err_ = 0;
    bool done_ = false;
};

}  // namespace penink
