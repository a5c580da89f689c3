// Fuzz target: flight path CSV text: parse_flight_path.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "scene/flight_path.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    try {
        parse_flight_path(std::string(reinterpret_cast<const char*>(data), size), "path.csv");
    } catch (const Error&) {
    }
    return 0;
}
