// A fresh, empty folder under the system temp directory for one test, removed (with its
// contents) when the object goes away: named after the running GoogleTest test
// (penink_<pid>_<suite>_<test>) or after a caller-given tag (penink_<tag>_<pid>).
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace penink::test {

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        make("penink_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    }
    explicit TempDir(const std::string& tag) { make("penink_" + tag + "_" + std::to_string(::getpid())); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    ~TempDir() { std::filesystem::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }

private:
    void make(const std::string& leaf) {
        path = std::filesystem::temp_directory_path() / leaf;
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
};

}  // namespace penink::test
