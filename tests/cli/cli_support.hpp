// Runs the penink binary in a fresh temporary directory and captures exit code and stderr.
#pragma once
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace penink::test {

struct RunResult {
    int code = -1;
    std::string output;  // stdout + stderr
};

// `command` replaces the binary and its arguments when given (a wrapper around them).
inline RunResult run_penink(const std::string& args, const std::filesystem::path& cwd, const std::string& command = "") {
    const std::string cmd = "cd '" + cwd.string() + "' && " +
                            (command.empty() ? "'" PENINK_BINARY_PATH "' " + args : command) + " 2>&1";
    RunResult r;
    FILE* p = popen(cmd.c_str(), "r");
    std::array<char, 4096> buf{};
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// run_penink, but as user nobody when the tests run as root (who may write any folder): for
// the cases of a folder that cannot be written. HOME is `cwd` (a user cache folder of its own).
inline RunResult run_penink_unprivileged(const std::string& args, const std::filesystem::path& cwd) {
    if (::geteuid() != 0) return run_penink(args, cwd);
    return run_penink("", cwd, "HOME='" + cwd.string() + "' setpriv --reuid=65534 --regid=65534 --clear-groups '" PENINK_BINARY_PATH "' " + args);
}

inline std::filesystem::path fresh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("penink_cli_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
    std::ofstream(p) << text;
}

inline std::size_t file_count(const std::filesystem::path& dir) {
    std::size_t n = 0;
    for (auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file();
    return n;
}

inline std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace penink::test
