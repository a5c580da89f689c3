// What the fuzz targets share: the input bytes as a file with a given name (for readers that take
// a path), one per process in the temp folder and rewritten for every input. Every target
// catches penink::Error, the one way bad input may end; anything else escaping (another
// exception, a crash, a sanitizer report) is a finding.
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace penink::fuzz {

inline std::string input_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("penink_fuzz_" + std::to_string(::getpid()) + "_" + name)).string();
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path;
}

}  // namespace penink::fuzz
