#include "core/memory_budget.hpp"

#include <unistd.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace penink {

std::uint64_t available_memory_bytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::uint64_t kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit)
        if (key == "MemAvailable:") return kib * 1024;
    const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
}

std::optional<std::uint64_t> parse_byte_size(const std::string& text) {
    double v = 0.0;
    const char* b = text.data();
    const char* e = b + text.size();
    const auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || p == b || !std::isfinite(v) || v <= 0.0) return std::nullopt;
    std::string unit;
    for (const char* q = p; q != e; ++q) unit += char(std::tolower(static_cast<unsigned char>(*q)));
    if (!unit.empty() && unit != "b") {
        if (unit.size() >= 2 && unit.substr(unit.size() - 2) == "ib") unit.erase(unit.size() - 2);
        else if (unit.back() == 'b') unit.pop_back();
    } else {
        unit.clear();
    }
    double scale = 1.0;
    if (unit == "k") scale = 1024.0;
    else if (unit == "m") scale = 1024.0 * 1024.0;
    else if (unit == "g") scale = 1024.0 * 1024.0 * 1024.0;
    else if (unit == "t") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
    else if (!unit.empty()) return std::nullopt;
    const double bytes = std::floor(v * scale);
    if (bytes < 1.0 || bytes > std::ldexp(1.0, 62)) return std::nullopt;
    return std::uint64_t(bytes);
}

std::string format_bytes(double bytes) {
    static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
    char s[48];
    if (u >= 3) std::snprintf(s, sizeof s, "%.1f %s", bytes, units[u]);
    else std::snprintf(s, sizeof s, "%.0f %s", bytes, units[u]);
    return s;
}

std::uint64_t memory_budget(std::uint64_t max_memory) { return max_memory > 0 ? max_memory : available_memory_bytes(); }

void check_memory(const std::string& stage, const std::string& file, const std::string& what, double need,
                  std::uint64_t budget) {
    if (budget == 0 || !(need > double(budget))) return;
    throw Error(stage, file, what + " would need about " + format_bytes(need) + " of memory, " +
                                 format_bytes(double(budget)) + " available (--max-memory)");
}

}  // namespace penink
