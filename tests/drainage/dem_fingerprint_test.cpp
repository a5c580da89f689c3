// The DEM fingerprint that keys both caches (drainage_db.hpp): the whole content and the side
// files, so a DEM changed in place with the same size and mtime, or a replaced .prj, is stale.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>

#include <fstream>

#include "core/error.hpp"
#include "drainage/drainage_db.hpp"
#include "support/temp_dir.hpp"

using namespace penink;
using namespace penink::test;

namespace {

// Overwrites one byte at `at` and puts the file's mtime back.
void flip_keeping_mtime(const std::string& path, std::size_t at) {
    struct stat st {};
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    {
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(at));
        f.put('#');
    }
    const timespec times[2] = {st.st_atim, st.st_mtim};
    ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, 0), 0);
}

}  // namespace

TEST(DemFingerprint, TheMiddleOfTheDemAndItsPrjCount) {
    TempDir dir("fingerprint");
    const std::string dem = dir.file("dem.asc");
    std::ofstream(dem) << std::string(5 << 20, '1');  // 5 MiB: the middle is beyond the first and last MiB
    const DrainageFingerprint a = dem_fingerprint(dem, 1);
    flip_keeping_mtime(dem, 5 << 19);
    const DrainageFingerprint b = dem_fingerprint(dem, 1);
    EXPECT_EQ(a.file_size, b.file_size);
    EXPECT_EQ(a.mtime_ns, b.mtime_ns);
    EXPECT_NE(a.content_hash, b.content_hash);
    std::ofstream(dir.file("dem.prj")) << "PROJCS[\"NZTM\"]";
    const DrainageFingerprint c = dem_fingerprint(dem, 1);
    EXPECT_NE(b.content_hash, c.content_hash);
    std::ofstream(dir.file("dem.prj")) << "PROJCS[\"UTM 60S\"]";
    EXPECT_NE(dem_fingerprint(dem, 1).content_hash, c.content_hash);
    EXPECT_EQ(dem_fingerprint(dem, 1).content_hash, dem_fingerprint(dem, 1).content_hash);  // deterministic
}

TEST(DemFingerprint, ANonRegularFileIsRefused) {
    try {
        dem_fingerprint("/dev/zero", 1);
        FAIL() << "/dev/zero fingerprinted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: input: /dev/zero: not a regular file (a device)");
    }
}
