// Writing a cache file whole (the terrain cache, the drainage lines' tile files): the parts'
// bytes, one after another, go to `PATH.tmp-PID` beside PATH, which is renamed onto PATH only
// when every byte is written and the file closed; on any failure the temporary is removed and
// PATH keeps what it held. No fsync: a cache checks itself when read (lengths, checksums), so a
// crash leaving it short costs only a rebuild. Outputs the user asked for go through
// export/atomic_file.hpp instead (flushed, placed together).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace penink {

// 0 when PATH holds the parts' bytes, else the errno of the first failed call (EIO when the
// system gave none).
int write_cache_file(const std::string& path, const std::vector<std::span<const std::uint8_t>>& parts);

}  // namespace penink
