// Fuzz target: scene files (TOML): load_scene (the mesh keys, and the [style] table over the named
// style, among them), validate_scene.
#include "fuzz/fuzz_input.hpp"

#include "core/error.hpp"
#include "scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    const std::string path = fuzz::input_file(data, size, "scene.toml");
    try {
        const Scene s = load_scene(path, "technical");  // no style file read
        validate_scene(s);
    } catch (const Error&) {
    }
    return 0;
}
