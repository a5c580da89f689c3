// Fuzz target: OFF meshes: read_mesh (CGAL's reader, triangulation, welding, the range check).
#include "fuzz/fuzz_input.hpp"

#include "core/error.hpp"
#include "input/mesh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    const std::string path = fuzz::input_file(data, size, "mesh.off");
    try {
        read_mesh(path);
    } catch (const Error&) {
    }
    return 0;
}
