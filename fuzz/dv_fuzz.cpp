// Fuzz target: the drainage cache reader. The input's first byte chooses whether its checksums
// are set right first (odd: the rest of the file reaches the parser instead of stopping at the
// checksum), the rest is the file: decoded from memory (decode_drainage_db) and read from a file
// (read_drainage_db, both parts and lines alone; read_drainage_line_index, then every vertex read
// from the file, block by block).
#include <algorithm>
#include <cstring>
#include <vector>

#include "fuzz/fuzz_input.hpp"

#include "core/error.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/dv_format.hpp"

namespace {

// The total length, the network part's and the lines part's checksums set to match the bytes,
// when the offset of the lines part is one the layout allows.
void set_checksums(std::vector<std::uint8_t>& b) {
    using namespace penink::dv;
    const std::uint64_t total = b.size();
    if (total < prefix_bytes + 16) return;
    std::uint64_t lines_at = 0;
    std::memcpy(&lines_at, b.data() + lines_at_at, 8);
    if (lines_at % 8 || lines_at < prefix_bytes + 8 || lines_at > total - 8) return;
    std::memcpy(b.data() + total_length_at, &total, 8);
    const std::uint64_t net = network_hash(b.data(), lines_at);
    std::memcpy(b.data() + lines_at - 8, &net, 8);
    const std::uint64_t lines = lines_hash(b.data() + lines_at, std::size_t(total - 8 - lines_at), lines_at, total);
    std::memcpy(b.data() + total - 8, &lines, 8);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penink;
    if (size == 0) return 0;
    std::vector<std::uint8_t> bytes(data + 1, data + size);
    if (data[0] & 1) set_checksums(bytes);
    try {
        decode_drainage_db(bytes, "fuzz");
    } catch (const Error&) {
    }
    const std::string path = fuzz::input_file(bytes.data(), bytes.size(), "cache");
    for (const DvParts parts : {DvParts::all, DvParts::lines}) {
        try {
            read_drainage_db(path, nullptr, parts);
        } catch (const Error&) {
        }
    }
    try {
        DvLineVertices vertices;
        read_drainage_line_index(path, nullptr, vertices);
        std::vector<DrapedVertex> out(1024);  // every vertex, a block's worth at a time (checked by block)
        for (int set = 0; set < 2; ++set)
            for (std::uint64_t first = 0; first < vertices.count[set]; first += out.size())
                vertices.read(set, first, std::min<std::uint64_t>(out.size(), vertices.count[set] - first), out.data());
    } catch (const Error&) {
    }
    return 0;
}
