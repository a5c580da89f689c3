// Input file checks and the outputs-are-not-inputs check (input_files.hpp), POSIX stat.
#include "core/input_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"
#include "core/printable_text.hpp"

namespace penink {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = char(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    return s;
}

// "/vsicurl/...", "/vsis3/", "/vsizip/" (any /vs prefix), "http://", "s3://", "ftp:" ...
bool network_or_virtual(const std::string& path) {
    const std::string p = lower(path);
    if (p.rfind("/vs", 0) == 0) return true;
    const std::size_t colon = p.find(':');
    if (colon == std::string::npos || colon == 0) return false;
    for (std::size_t i = 0; i < colon; ++i)
        if (!((p[i] >= 'a' && p[i] <= 'z') || (p[i] >= '0' && p[i] <= '9') || p[i] == '+' || p[i] == '-' || p[i] == '.'))
            return false;
    const std::string scheme = p.substr(0, colon);
    if (p.compare(colon, 3, "://") == 0) return true;
    for (const char* s : {"http", "https", "ftp", "ftps", "file", "s3", "gs", "az", "wms", "wmts", "wcs", "pg", "mysql"})
        if (scheme == s) return true;
    return false;
}

std::string kind_of(mode_t m) {
    if (S_ISDIR(m)) return "a folder";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m) || S_ISBLK(m)) return "a device";
    if (S_ISSOCK(m)) return "a socket";
    return "not a plain file";
}

std::string mib(std::uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::string shown_path(const std::string& path) {
    const std::string p = printable_text(path, 4096);
    return p;
}

void check_local_path(const std::string& stage, const std::string& path) {
    if (path.find('\0') != std::string::npos) throw Error(stage, shown_path(path), "path holds a NUL byte");
    if (network_or_virtual(path))
        throw Error(stage, shown_path(path), "is a network or virtual path (penink reads local files only)");
}

void check_input_file(const std::string& stage, const std::string& path, std::uint64_t max_bytes,
                      const std::string& what) {
    check_local_path(stage, path);
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(stage, shown_path(path), errno == ENOENT ? "no such file" : std::string("cannot read file (") + std::strerror(errno) + ")");
    if (!S_ISREG(st.st_mode)) throw Error(stage, shown_path(path), "not a regular file (" + kind_of(st.st_mode) + ")");
    if (max_bytes > 0 && std::uint64_t(st.st_size) > max_bytes)
        throw Error(stage, shown_path(path), "file of " + std::to_string(st.st_size) + " bytes is larger than the " +
                                                 mib(max_bytes) + " " + what + " may have");
}

std::string read_input_text(const std::string& stage, const std::string& path, std::uint64_t max_bytes,
                            const std::string& what) {
    check_input_file(stage, path, max_bytes, what);
    // O_NONBLOCK: a file swapped for a FIFO after the check does not block the open
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throw Error(stage, shown_path(path), std::string("cannot read file (") + std::strerror(errno) + ")");
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        throw Error(stage, shown_path(path), "not a regular file (" + kind_of(st.st_mode) + ")");
    }
    std::string text;
    char buf[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int err = errno;
            ::close(fd);
            throw Error(stage, shown_path(path), std::string("cannot read file (") + std::strerror(err) + ")");
        }
        if (n == 0) break;
        text.append(buf, std::size_t(n));
        if (max_bytes > 0 && text.size() > max_bytes) {  // grew since the check
            ::close(fd);
            throw Error(stage, shown_path(path), "file is larger than the " + mib(max_bytes) + " " + what + " may have");
        }
    }
    ::close(fd);
    return text;
}

void check_toml_nesting(const std::string& stage, const std::string& path, const std::string& text, int max_depth) {
    int depth = 0, dots = 0;  // dots: of the dotted key (or number) since the last = [ ] { } , or newline
    const std::size_t n = text.size();
    for (std::size_t i = 0; i < n; ++i) {
        const char c = text[i];
        if (c == '=' || c == '[' || c == ']' || c == '{' || c == '}' || c == ',' || c == '\n') dots = 0;
        if (c == '.' && ++dots >= max_depth)  // parts = dots + 1
            throw Error(stage, shown_path(path), "TOML key has more than " + std::to_string(max_depth) + " dotted parts");
        if (c == '#') {  // a comment to the end of the line
            while (i < n && text[i] != '\n') ++i;
        } else if (c == '"' || c == '\'') {
            const bool multi = i + 2 < n && text[i + 1] == c && text[i + 2] == c;
            const bool basic = c == '"';
            i += multi ? 3 : 1;
            for (; i < n; ++i) {
                if (basic && text[i] == '\\') {
                    ++i;
                    continue;
                }
                if (text[i] == c && (!multi || (i + 2 < n && text[i + 1] == c && text[i + 2] == c))) {
                    if (multi) i += 2;
                    break;
                }
                if (!multi && text[i] == '\n') break;  // unterminated: the parser says so
            }
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                throw Error(stage, shown_path(path),
                            "TOML nests brackets or braces deeper than " + std::to_string(max_depth) + " levels");
        } else if (c == ']' || c == '}') {
            depth = depth > 0 ? depth - 1 : 0;
        }
    }
}

void check_outputs_not_inputs(const std::string& stage, const std::vector<std::string>& outputs,
                              const std::vector<NamedInput>& inputs) {
    std::vector<std::pair<struct stat, const NamedInput*>> ids;
    for (const NamedInput& in : inputs) {
        struct stat st {};
        if (in.path.empty() || in.path.find('\0') != std::string::npos || ::stat(in.path.c_str(), &st) != 0) continue;
        ids.push_back({st, &in});
    }
    for (const std::string& out : outputs) {
        struct stat st {};
        if (out.find('\0') != std::string::npos) throw Error(stage, shown_path(out), "path holds a NUL byte");
        if (::stat(out.c_str(), &st) != 0) continue;
        for (const auto& [id, in] : ids)
            if (id.st_dev == st.st_dev && id.st_ino == st.st_ino)
                throw Error(stage, shown_path(out),
                            "is " + in->role + " " + shown_path(in->path) + " (an output never replaces an input)");
    }
}

}  // namespace penink
