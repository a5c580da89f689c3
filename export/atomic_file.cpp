// Temp file + rename (atomic_file.hpp), POSIX mkstemp/rename.
#include "export/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/error.hpp"

namespace penink {

namespace {

[[noreturn]] void fail(const std::string& path, int err) {
    throw Error("export", path, std::string("cannot write file (") + std::strerror(err) + ")");
}

// Creates PATH.tmp-XXXXXX; returns its name and an open descriptor.
std::string make_temp(const std::string& path, int& fd) {
    std::string name = path + ".tmp-XXXXXX";
    std::vector<char> buf(name.begin(), name.end());
    buf.push_back('\0');
    fd = ::mkstemp(buf.data());
    if (fd < 0) fail(path, errno);
    ::fchmod(fd, 0644);
    return std::string(buf.data());
}

bool write_all(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd, bytes.data(), bytes.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        bytes.remove_prefix(static_cast<size_t>(n));
    }
    return true;
}

void commit(const std::string& temp, const std::string& path) {
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        fail(path, err);
    }
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view bytes) {
    int fd = -1;
    const std::string temp = make_temp(path, fd);
    const bool ok = write_all(fd, bytes);
    const int err = ok ? 0 : (errno ? errno : EIO);
    if (::close(fd) != 0 || !ok) {
        const int e = ok ? errno : err;
        ::unlink(temp.c_str());
        fail(path, e);
    }
    commit(temp, path);
}

void write_files_together(const std::vector<std::string>& paths,
                          const std::function<std::string(std::size_t)>& bytes_of) {
    std::vector<std::string> temps;
    auto remove_temps = [&temps] {
        for (const std::string& t : temps) ::unlink(t.c_str());
    };
    try {
        for (std::size_t i = 0; i < paths.size(); ++i) {
            const std::string bytes = bytes_of(i);
            int fd = -1;
            temps.push_back(make_temp(paths[i], fd));
            const bool ok = write_all(fd, bytes);
            const int err = ok ? 0 : (errno ? errno : EIO);
            if (::close(fd) != 0 || !ok) fail(paths[i], ok ? errno : err);
        }
    } catch (...) {
        remove_temps();
        throw;
    }
    for (std::size_t i = 0; i < paths.size(); ++i)
        if (::rename(temps[i].c_str(), paths[i].c_str()) != 0) {
            const int err = errno;
            temps.erase(temps.begin(), temps.begin() + std::ptrdiff_t(i));
            remove_temps();
            fail(paths[i], err);
        }
}

}  // namespace penink
