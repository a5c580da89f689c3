// A folder whose files a test writes first and that is then read-only to penink: chmod 0555 for
// a user other than root; as root (who writes through any mode) a small tmpfs mounted there and
// remounted read-only, unmounted when the object goes away. `reason` is set when neither works
// (root without the right to mount): the test then skips, saying why.
#pragma once
#include <sys/mount.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace penink::test {

class ReadOnlyDir {
public:
    // Makes the folder `path` (new or empty) writable for now.
    explicit ReadOnlyDir(std::filesystem::path path) : path_(std::move(path)) {
        std::filesystem::create_directories(path_);
        if (::geteuid() == 0) {
            if (::mount("tmpfs", path_.c_str(), "tmpfs", 0, "size=64m") != 0)
                reason = "root, and a tmpfs cannot be mounted here (the folder would stay writable)";
            else
                mounted_ = true;
        }
    }
    ReadOnlyDir(const ReadOnlyDir&) = delete;
    ReadOnlyDir& operator=(const ReadOnlyDir&) = delete;
    ~ReadOnlyDir() {
        if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
        std::error_code ec;
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ec);
    }
    // The files written so far stay; nothing more can be written. False (and `reason`) if not.
    bool seal() {
        if (!reason.empty()) return false;
        if (mounted_) {
            if (::mount("tmpfs", path_.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=64m") != 0)
                return reason = "the tmpfs cannot be remounted read-only", false;
            return true;
        }
        std::filesystem::permissions(path_, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
        return true;
    }
    const std::filesystem::path& path() const { return path_; }
    std::string reason;

private:
    std::filesystem::path path_;
    bool mounted_ = false;
};

}  // namespace penink::test
