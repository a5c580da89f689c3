// Fuzz target: style files (TOML): load_style.
#include "fuzz/fuzz_input.hpp"

#include "core/error.hpp"
#include "export/style.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    const std::string path = fuzz::input_file(data, size, "style.toml");
    try {
        load_style(path);
    } catch (const Error&) {
    }
    return 0;
}
