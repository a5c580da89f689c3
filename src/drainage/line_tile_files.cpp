#include "drainage/line_tile_files.hpp"


#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/cache_file_write.hpp"
#include "core/hash64.hpp"

namespace penink {

namespace {

constexpr std::uint32_t magic = 0x544c4e50u;  // "PNLT"
constexpr std::uint32_t version = 1;

template <class T> void put(std::vector<std::uint8_t>& out, const T& v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), p, p + sizeof v);
}

struct Reader {
    const std::vector<std::uint8_t>& in;
    std::size_t at = 0;
    bool ok = true;
    template <class T> T get() {
        T v{};
        if (at + sizeof v > in.size()) {
            ok = false;
            return v;
        }
        std::memcpy(&v, in.data() + at, sizeof v);
        at += sizeof v;
        return v;
    }
};

}  // namespace

std::string line_tile_path(const std::string& folder, std::uint32_t tile) {
    return (std::filesystem::path(folder) / ("tile-" + std::to_string(tile) + ".pnlt")).string();
}

bool write_line_tile(const std::string& path, std::uint64_t key, const std::vector<std::uint32_t>& stems,
                     const DrapedLineSet& lines) {
    std::vector<std::uint8_t> out;
    out.reserve(32 + 4 * stems.size() + 5 * lines.lines.size() + sizeof(DrapedVertex) * lines.vertices.size() + 8);
    put(out, magic), put(out, version), put(out, key);
    put(out, std::uint32_t(stems.size())), put(out, std::uint32_t(lines.lines.size()));
    put(out, std::uint64_t(lines.vertices.size()));
    for (std::uint32_t s : stems) put(out, s);
    for (const DrapedLine& l : lines.lines) put(out, l.count), put(out, l.order);
    const auto* v = reinterpret_cast<const std::uint8_t*>(lines.vertices.data());
    out.insert(out.end(), v, v + sizeof(DrapedVertex) * lines.vertices.size());
    put(out, hash64(out.data(), out.size()));
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    return write_cache_file(path, {out}) == 0;
}

bool read_line_tile(const std::string& path, std::uint64_t key, std::vector<std::uint32_t>& stems,
                    DrapedLineSet& lines) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    const std::vector<std::uint8_t> in((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (in.size() < 8) return false;
    std::uint64_t sum;
    std::memcpy(&sum, in.data() + in.size() - 8, 8);
    if (hash64(in.data(), in.size() - 8) != sum) return false;
    Reader r{in};
    if (r.get<std::uint32_t>() != magic || r.get<std::uint32_t>() != version || r.get<std::uint64_t>() != key) return false;
    const auto ns = r.get<std::uint32_t>(), nl = r.get<std::uint32_t>();
    const auto nv = r.get<std::uint64_t>();
    if (!r.ok || in.size() - 8 - r.at != 4ull * ns + 5ull * nl + sizeof(DrapedVertex) * nv) return false;
    stems.resize(ns);
    for (std::uint32_t& s : stems) s = r.get<std::uint32_t>();
    lines = DrapedLineSet{};
    lines.lines.resize(nl);
    std::uint64_t first = 0;
    for (DrapedLine& l : lines.lines) {
        l.count = r.get<std::uint32_t>(), l.order = r.get<std::uint8_t>();
        l.first = std::uint32_t(first), first += l.count;
        if (l.count == 0) return false;
    }
    if (first != nv) return false;
    lines.vertices.resize(nv);
    std::memcpy(lines.vertices.data(), in.data() + r.at, sizeof(DrapedVertex) * nv);
    index_lines(lines);
    return line_set_ok(lines);
}

}  // namespace penink
