// write_cache_file and CacheFileStream: the parts' bytes in order (a stream's head written
// last), no temporary left, the old file kept on failure or when a stream is dropped.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "core/cache_file_write.hpp"
#include "support/temp_dir.hpp"

using namespace penink;
namespace fs = std::filesystem;

namespace {
std::string read_all(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST(CacheFileWrite, WritesThePartsInOrderAndLeavesNoTemporary) {
    test::TempDir dir;
    const std::string path = dir.file("c.bin");
    const std::vector<std::uint8_t> a{'a', 'b'}, empty, b{'c', 'd', 'e'};
    ASSERT_EQ(write_cache_file(path, {a, empty, b}), 0);
    EXPECT_EQ(read_all(path), "abcde");
    ASSERT_EQ(write_cache_file(path, {b}), 0);  // replaces the old file
    EXPECT_EQ(read_all(path), "cde");
    EXPECT_FALSE(fs::exists(path + ".tmp-" + std::to_string(::getpid())));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(CacheFileWrite, AFailedWriteKeepsTheOldFileAndSaysWhy) {
    test::TempDir dir;
    const std::string path = dir.file("c.bin");
    const std::vector<std::uint8_t> old{'o', 'l', 'd'};
    ASSERT_EQ(write_cache_file(path, {old}), 0);
    // the temporary's place taken by a folder: the open fails, PATH is untouched
    fs::create_directory(path + ".tmp-" + std::to_string(::getpid()));
    EXPECT_NE(write_cache_file(path, {std::vector<std::uint8_t>{'n', 'e', 'w'}}), 0);
    EXPECT_EQ(read_all(path), "old");
    // a path in a missing folder
    EXPECT_NE(write_cache_file(dir.file("missing/c.bin"), {old}), 0);
    EXPECT_FALSE(fs::exists(dir.file("missing")));
}

TEST(CacheFileWrite, AStreamWritesItsHeadLastAndNothingWhenDropped) {
    test::TempDir dir;
    const std::string path = dir.file("s.bin");
    {
        CacheFileStream out(path);
        const std::vector<std::uint8_t> zeros(3, 0), body{'d', 'a', 't', 'a'}, head{'H', 'D', 'R'};
        EXPECT_EQ(out.append(zeros), 0);
        EXPECT_EQ(out.append(body), 0);
        EXPECT_FALSE(fs::exists(path));  // nothing in place before finish
        EXPECT_EQ(out.finish(head), 0);
    }
    EXPECT_EQ(read_all(path), "HDRdata");
    {
        CacheFileStream out(path);  // dropped unfinished (an exception on the way): the old file stays
        out.append(std::vector<std::uint8_t>{'n', 'e', 'w'});
    }
    EXPECT_EQ(read_all(path), "HDRdata");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
    CacheFileStream bad(dir.file("missing/s.bin"));  // cannot open: every call says why
    EXPECT_NE(bad.append(std::vector<std::uint8_t>{'x'}), 0);
    EXPECT_NE(bad.finish(), 0);
    EXPECT_FALSE(fs::exists(dir.file("missing")));
}
