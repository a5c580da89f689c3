// A DEM file's identity from the file system (input/dem_file_identity.hpp): the same while nothing
// is written, another after any write to the DEM or a side file (even with its mtime put back),
// for a copy, or when a side file appears; 0 for a path that is no regular file.
#include <fcntl.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "input/dem_file_identity.hpp"
#include "support/temp_dir.hpp"

using namespace penink;

namespace {

// Rewrites one byte of `path` with the same byte and puts its mtime back: its content and mtime
// are as before, only its status-change time moves.
void rewrite_keeping_mtime(const std::string& path) {
    struct stat st {};
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // a ctime tick later, whatever the clock's grain
    {
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        const int c = f.get();
        f.seekp(0);
        f.put(char(c));
    }
    const timespec times[2] = {st.st_atim, st.st_mtim};
    ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, 0), 0);
    struct stat after {};
    ASSERT_EQ(::stat(path.c_str(), &after), 0);
    ASSERT_EQ(after.st_mtim.tv_nsec, st.st_mtim.tv_nsec);
    ASSERT_EQ(after.st_size, st.st_size);
}

}  // namespace

TEST(DemFileIdentity, ChangesWithAnyWriteCopyOrSideFile) {
    test::TempDir dir;
    const std::string dem = dir.file("dem.asc");
    std::ofstream(dem) << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n";
    const std::uint64_t a = dem_file_identity(dem);
    EXPECT_NE(a, 0u);
    EXPECT_EQ(dem_file_identity(dem), a);  // nothing written: the same

    rewrite_keeping_mtime(dem);  // same bytes, size and mtime
    const std::uint64_t b = dem_file_identity(dem);
    EXPECT_NE(b, a);
    EXPECT_EQ(dem_file_identity(dem), b);

    std::ofstream(dir.file("dem.prj")) << "PROJCS[\"NZTM\"]";  // a side file appears
    const std::uint64_t c = dem_file_identity(dem);
    EXPECT_NE(c, b);
    rewrite_keeping_mtime(dir.file("dem.prj"));  // and is written
    const std::uint64_t d = dem_file_identity(dem);
    EXPECT_NE(d, c);

    const std::string copy = dir.file("copy.asc");
    std::filesystem::copy_file(dem, copy);
    EXPECT_NE(dem_file_identity(copy), dem_file_identity(dem));
    std::filesystem::remove(dem);
    std::filesystem::rename(copy, dem);  // replaced by a file of the same bytes: another inode
    EXPECT_NE(dem_file_identity(dem), d);
}

TEST(DemFileIdentity, NoneForWhatIsNoRegularFile) {
    test::TempDir dir;
    EXPECT_EQ(dem_file_identity(dir.file("missing.tif")), 0u);
    EXPECT_EQ(dem_file_identity(dir.path.string()), 0u);
    EXPECT_EQ(dem_file_identity("/dev/null"), 0u);
}
