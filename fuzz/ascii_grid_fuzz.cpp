// Fuzz target: the ASCII-grid path of the DEM reader: read_dem of a .asc file (GDAL picks the
// driver; the seeds are ESRI ASCII grids), full read and heights-only read, with a memory budget
// that keeps an input's allocation under the fuzzer's limit.
#include "fuzz/fuzz_input.hpp"

#include "core/error.hpp"
#include "input/dem_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    const std::string path = fuzz::input_file(data, size, "grid.asc");
    for (const bool heights_only : {false, true}) {
        try {
            DemOptions o;
            o.heights_only = heights_only;
            o.max_memory = std::uint64_t(256) << 20;
            read_dem(path, o);
        } catch (const Error&) {
        }
    }
    return 0;
}
