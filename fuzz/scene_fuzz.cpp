// Fuzz target: scene files (TOML): load_scene, validate_scene, the mesh keys and the [style] table
// over the named style.
#include "fuzz/fuzz_input.hpp"

#include "core/error.hpp"
#include "scene/mesh_scene.hpp"
#include "scene/scene.hpp"
#include "scene/scene_style.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    const std::string path = fuzz::input_file(data, size, "scene.toml");
    try {
        Scene s = load_scene(path);
        validate_scene(s);
        load_mesh_scene(s);
        if (s.style != "technical" && s.style != "field-sketch") s.style = "technical";  // no other file read
        scene_style(s);
    } catch (const Error&) {
    }
    return 0;
}
