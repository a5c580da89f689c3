// All or none for a set of outputs (atomic_file.hpp): a failure to place the second file puts
// the first one back; a full disk is an error with nothing left; the temporaries and kept old
// files of a killed run are cleaned up (or put back) by the next write beside them.
#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

std::string text_of(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void put(const std::string& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// A process id that runs no more: a child that has exited and been reaped.
pid_t gone_pid() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return pid;
}

}  // namespace

TEST(AtomicPlacement, FailureToPlaceTheSecondPutsTheFirstBack) {
    TempDir dir("placement");
    const std::vector<std::string> paths = {dir.file("imm.svg"), dir.file("imm.png")};
    put(paths[0], "old svg");
    put(paths[1], "old png");
    // The second temporary made a folder: its rename onto the file imm.png fails (ENOTDIR) after
    // imm.svg has been placed.
    std::string second_temp;
    try {
        write_atomically_together(paths, [&](std::size_t i, const std::string& temp) {
            put(temp, "new " + std::to_string(i));
            if (i == 1) {
                fs::remove(temp);
                fs::create_directory(temp);
                put(temp + "/inside", "x");
                second_temp = temp;
            }
        });
        FAIL() << "placing a folder onto a file succeeded";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: export: " + paths[1] + ": cannot write file (Not a directory)");
    }
    EXPECT_EQ(text_of(paths[0]), "old svg");  // rolled back
    EXPECT_EQ(text_of(paths[1]), "old png");
    fs::remove_all(second_temp);  // the folder this test made (not a file penink can remove)
    EXPECT_EQ(names_in(dir.path), (std::vector<std::string>{"imm.png", "imm.svg"}));
}

TEST(AtomicPlacement, AFileThatDidNotExistIsRemovedOnRollBack) {
    TempDir dir("placement_new");
    const std::vector<std::string> paths = {dir.file("a.svg"), dir.file("b.png")};
    put(paths[1], "old png");
    std::string second_temp;
    EXPECT_THROW(write_atomically_together(paths, [&](std::size_t i, const std::string& temp) {
        if (i == 1) fs::remove(temp), fs::create_directory(temp), put(temp + "/x", "x"), second_temp = temp;
    }), Error);
    fs::remove_all(second_temp);
    EXPECT_EQ(names_in(dir.path), std::vector<std::string>{"b.png"});
    EXPECT_EQ(text_of(paths[1]), "old png");
}

TEST(AtomicPlacement, FullDiskIsAnErrorAndLeavesNothing) {
    TempDir dir("placement_full");
    const fs::path mnt = dir.path / "small";
    fs::create_directory(mnt);
    if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=1m") != 0)
        GTEST_SKIP() << "cannot mount a 1 MiB tmpfs here (" << std::strerror(errno) << "): needs root or CAP_SYS_ADMIN";
    const std::vector<std::string> paths = {(mnt / "a.svg").string(), (mnt / "b.png").string()};
    put(paths[0], "old");
    try {
        write_files_together(paths, [](std::size_t i) { return std::string(i == 0 ? 100 : 3 << 20, 'x'); });
        ADD_FAILURE() << "3 MiB written to a 1 MiB file system";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "penink: export: " + paths[1] + ": cannot write file (No space left on device)");
    }
    const std::vector<std::string> left = names_in(mnt);
    const std::string old = text_of(paths[0]);
    ::umount(mnt.c_str());
    EXPECT_EQ(left, std::vector<std::string>{"a.svg"});
    EXPECT_EQ(old, "old");
}

TEST(AtomicPlacement, AKilledRunsLeftoversAreCleanedByTheNextWrite) {
    TempDir dir("placement_stale");
    const std::string a = dir.file("a.svg"), b = dir.file("b.png"), c = dir.file("c.pdf");
    const std::string dead = ".penink-" + std::to_string(gone_pid());
    // Killed after a.svg was renamed aside-kept and replaced, before b.png's rename, c.pdf new:
    put(a, "new a");
    put(a + dead + ".old", "old a");       // a's earlier file, kept: goes back
    put(b, "old b");
    put(b + dead + ".tmp-Ab12Cd", "new b");  // b's temporary: removed
    put(c, "new c");
    put(c + dead + ".none", "");           // c did not exist before: removed
    const std::string live = a + ".penink-" + std::to_string(::getppid()) + ".tmp-XyZ123";  // a running process's
    put(live, "theirs");
    remove_stale_temporaries(a);
    remove_stale_temporaries(b);
    remove_stale_temporaries(c);
    EXPECT_EQ(text_of(a), "old a");
    EXPECT_EQ(text_of(b), "old b");
    EXPECT_FALSE(fs::exists(c));
    EXPECT_EQ(names_in(dir.path), (std::vector<std::string>{"a.svg", fs::path(live).filename().string(), "b.png"}));
    // A write beside a path cleans up as it goes.
    put(b + dead + ".tmp-Zz99Yy", "stale");
    write_file_atomically(b, "newest b");
    EXPECT_EQ(text_of(b), "newest b");
    EXPECT_EQ(names_in(dir.path), (std::vector<std::string>{"a.svg", fs::path(live).filename().string(), "b.png"}));
}
