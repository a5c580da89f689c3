#include "core/huge_page_malloc.hpp"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace penink {

namespace {

constexpr const char* tunable = "glibc.malloc.hugetlb";

}  // namespace

bool kernel_gives_huge_pages() {
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string modes;
    return std::getline(f, modes) && modes.find("[never]") == std::string::npos;
}

std::string huge_page_tunables(const char* current) {
    if (current && std::strstr(current, tunable)) return {};
    return (current && *current ? std::string(current) + ":" : std::string()) + tunable + "=1";
}

bool heap_in_huge_pages() {
    const char* set = std::getenv("GLIBC_TUNABLES");
    return set && std::strstr(set, tunable);
}

void restart_with_huge_page_malloc(char** argv) noexcept {
    try {
        const char* set = std::getenv("GLIBC_TUNABLES");
        const std::string with = huge_page_tunables(set);
        if (with.empty()) return;
        if (const char* off = std::getenv("PENINK_HUGE_PAGES"); off && std::strcmp(off, "0") == 0) return;
        if (const char* preload = std::getenv("LD_PRELOAD"); preload && std::strstr(preload, "vgpreload")) return;
        if (!kernel_gives_huge_pages()) return;
        char exe[4096];
        const ssize_t n = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
        if (n <= 0) return;
        exe[n] = '\0';
        const std::string before = set ? set : "";
        if (::setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0) return;
        ::execv(exe, argv);
        // the restart failed: the environment as it was
        if (set) ::setenv("GLIBC_TUNABLES", before.c_str(), 1);
        else ::unsetenv("GLIBC_TUNABLES");
    } catch (...) {  // (a string's allocation: go on as it is)
    }
}

}  // namespace penink
