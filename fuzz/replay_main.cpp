// Replays a fuzz corpus without libFuzzer (any compiler): `fuzz_replay TARGET DIR...` feeds every
// file under each DIR, in name order, to TARGET's LLVMFuzzerTestOneInput (renamed
// penink_fuzz_TARGET in this build: fuzz_replay_targets.cpp, generated) and prints how many ran.
// A crash or an escaping exception fails the run, so a fixed finding stays fixed.
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_replay_targets.hpp"

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    if (argc < 3) {
        std::fprintf(stderr, "usage: fuzz_replay TARGET DIR...\n");
        return 2;
    }
    const penink::fuzz::Target* target = penink::fuzz::find_target(argv[1]);
    if (!target) {
        std::fprintf(stderr, "fuzz_replay: no target %s\n", argv[1]);
        return 2;
    }
    std::vector<fs::path> files;
    for (int i = 2; i < argc; ++i)
        for (const auto& e : fs::recursive_directory_iterator(argv[i]))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        std::ifstream in(f, std::ios::binary);
        const std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
        target->run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    const std::string mine = "penink_fuzz_" + std::to_string(::getpid()) + "_";  // fuzz_input.hpp's files
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
        if (e.path().filename().string().rfind(mine, 0) == 0) fs::remove(e.path());
    std::printf("fuzz_replay %s: %zu inputs\n", argv[1], files.size());
    return files.empty() ? 1 : 0;
}
