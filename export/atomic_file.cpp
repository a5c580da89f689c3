// Temp file + flush + rename with kept old files (atomic_file.hpp), POSIX.
#include "export/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.hpp"

namespace penink {

namespace {

[[noreturn]] void fail(const std::string& path, int err) {
    throw Error("export", path, std::string("cannot write file (") + std::strerror(err ? err : EIO) + ")");
}

std::string tag() { return ".penink-" + std::to_string(::getpid()); }
std::string old_name(const std::string& path) { return path + tag() + ".old"; }
std::string none_name(const std::string& path) { return path + tag() + ".none"; }

std::string folder_of(const std::string& path) {
    const std::string dir = std::filesystem::path(path).parent_path().string();
    return dir.empty() ? "." : dir;
}

// Creates PATH.penink-PID.tmp-XXXXXX; returns its name and an open descriptor.
std::string make_temp(const std::string& path, int& fd) {
    remove_stale_temporaries(path);
    std::string name = path + tag() + ".tmp-XXXXXX";
    std::vector<char> buf(name.begin(), name.end());
    buf.push_back('\0');
    fd = ::mkstemp(buf.data());
    if (fd < 0) fail(path, errno);
    ::fchmod(fd, 0644);
    return std::string(buf.data());
}

// 0, or the errno of a failed or short write.
int write_all(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd, bytes.data(), bytes.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;
        bytes.remove_prefix(static_cast<size_t>(n));
    }
    return 0;
}

// Writes, flushes and closes; 0 or the first error.
int write_flush_close(int fd, std::string_view bytes) {
    int err = write_all(fd, bytes);
    if (err == 0 && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) err = errno;  // EINVAL: a pipe-like file
    if (::close(fd) != 0 && err == 0) err = errno;
    return err;
}

// Flushes a file written by a library (by name).
int flush_file(const std::string& name) {
    const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return errno;
    int err = 0;
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) err = errno;
    ::close(fd);
    return err;
}

void flush_folder(const std::string& path) {
    const int fd = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);  // best effort: the renames are durable once the folder is
    ::close(fd);
}

bool exists_no_follow(const std::string& p) {
    struct stat st {};
    return ::lstat(p.c_str(), &st) == 0;
}

// Places temps[i] onto paths[i] for every i, keeping each old file until all are in; on a
// failure puts the old ones back and throws. The temps are gone either way.
void place_together(const std::vector<std::string>& paths, std::vector<std::string>& temps) {
    std::size_t placed = 0;
    std::vector<char> had_old(paths.size(), 0);
    auto roll_back = [&] {
        for (std::size_t j = placed; j-- > 0;) {
            if (had_old[j]) {
                ::rename(old_name(paths[j]).c_str(), paths[j].c_str());
            } else {
                ::unlink(paths[j].c_str());
                ::unlink(none_name(paths[j]).c_str());
            }
        }
        for (std::size_t j = placed; j < paths.size(); ++j) {
            if (had_old[j]) ::unlink(old_name(paths[j]).c_str());
            ::unlink(none_name(paths[j]).c_str());
        }
        for (const std::string& t : temps) ::unlink(t.c_str());
    };
    // First every old file kept (a hard link) or its absence marked, then the renames.
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const std::string old = old_name(paths[i]);
        ::unlink(old.c_str());
        if (exists_no_follow(paths[i])) {
            if (::link(paths[i].c_str(), old.c_str()) != 0) {
                const int err = errno;
                roll_back();
                fail(paths[i], err);
            }
            had_old[i] = 1;
        } else {
            const int fd = ::open(none_name(paths[i]).c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
            if (fd < 0) {
                const int err = errno;
                roll_back();
                fail(paths[i], err);
            }
            ::close(fd);
        }
    }
    for (; placed < paths.size(); ++placed)
        if (::rename(temps[placed].c_str(), paths[placed].c_str()) != 0) {
            const int err = errno;
            roll_back();
            fail(paths[placed], err);
        }
    for (const std::string& p : paths) flush_folder(p);
    for (std::size_t i = 0; i < paths.size(); ++i)
        ::unlink((had_old[i] ? old_name(paths[i]) : none_name(paths[i])).c_str());
    temps.clear();
}

bool process_gone(long pid) { return pid > 0 && pid != long(::getpid()) && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH; }

}  // namespace

void remove_stale_temporaries(const std::string& path) {
    const std::string dir = folder_of(path);
    const std::string base = std::filesystem::path(path).filename().string() + ".penink-";
    DIR* d = ::opendir(dir.c_str());
    if (!d) return;
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(d)) {
        const std::string n = e->d_name;
        if (n.compare(0, base.size(), base) == 0) names.push_back(n);
    }
    ::closedir(d);
    for (const std::string& n : names) {
        char* end = nullptr;
        const long pid = std::strtol(n.c_str() + base.size(), &end, 10);
        if (end == n.c_str() + base.size() || !process_gone(pid)) continue;
        const std::string rest = end, full = (std::filesystem::path(dir) / n).string();
        if (rest == ".old") {  // killed while placing: the earlier file goes back
            ::rename(full.c_str(), path.c_str());
        } else if (rest == ".none") {  // killed while placing: there was no file before
            ::unlink(path.c_str());
            ::unlink(full.c_str());
        } else if (rest.compare(0, 5, ".tmp-") == 0) {
            ::unlink(full.c_str());
        }
    }
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
    write_files_together({path}, [&](std::size_t) { return std::string(bytes); });
}

void write_files_together(const std::vector<std::string>& paths,
                          const std::function<std::string(std::size_t)>& bytes_of) {
    std::vector<std::string> temps;
    try {
        for (std::size_t i = 0; i < paths.size(); ++i) {
            const std::string bytes = bytes_of(i);
            int fd = -1;
            temps.push_back(make_temp(paths[i], fd));
            if (const int err = write_flush_close(fd, bytes)) fail(paths[i], err);
        }
    } catch (...) {
        for (const std::string& t : temps) ::unlink(t.c_str());
        throw;
    }
    place_together(paths, temps);
}

void write_atomically_together(const std::vector<std::string>& paths,
                               const std::function<void(std::size_t, const std::string&)>& write) {
    std::vector<std::string> temps;
    try {
        for (std::size_t i = 0; i < paths.size(); ++i) {
            int fd = -1;
            temps.push_back(make_temp(paths[i], fd));
            ::close(fd);
            write(i, temps.back());
            if (const int err = flush_file(temps.back())) fail(paths[i], err);
        }
    } catch (...) {
        for (const std::string& t : temps) ::unlink(t.c_str());
        throw;
    }
    place_together(paths, temps);
}

}  // namespace penink
