// The memory a command may use and what an input would need: the budget (--max-memory, else the
// memory the system has available: /proc/meminfo MemAvailable, else sysconf's free pages), byte
// sizes as people write them ("2G", "512M", "1.5GiB", "3000000") and print them ("2.0 GiB"), and
// the check every stage runs before it allocates: an estimate (cells times bytes per cell) that
// exceeds the budget is a bad-input error naming what the input would need.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace penink {

// Bytes the system has available now (MemAvailable); 0 when it cannot be told.
std::uint64_t available_memory_bytes();

// "2G", "2GB", "2GiB", "512M", "64k", "1.5G", "3000000" (bytes): K/M/G/T are powers of 1024,
// case-insensitive, optional "B"/"iB". nullopt for anything else, zero, or more than 2^62 bytes.
std::optional<std::uint64_t> parse_byte_size(const std::string& text);

// "512 MiB", "2.0 GiB", "19.3 TiB" (one decimal from GiB on), "812 KiB", "100 B".
std::string format_bytes(double bytes);

// The budget a command works within: `max_memory` when > 0, else available_memory_bytes() (0:
// unknown, no limit).
std::uint64_t memory_budget(std::uint64_t max_memory);

// Throws Error(stage, file, "<what> would need about <need> of memory, <budget> available
// (--max-memory)") when budget > 0 and need > budget; `what` names the input, e.g. "the DEM's
// 50000x50000 nodes".
void check_memory(const std::string& stage, const std::string& file, const std::string& what, double need,
                  std::uint64_t budget);

}  // namespace penink
