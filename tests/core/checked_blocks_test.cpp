// Arrays read on demand: a byte range reads exactly the blocks holding it (counted), once; what
// is read is the file's bytes; a damaged block throws DamagedBlockError naming the file and the
// block when it is read, the sound blocks read with it stay read, and a block never read is
// never checked. A strided read (every k-th element) gives what need and the mapping give, its
// blocks checked but not kept; so does a read one element at a time through a small cache of
// blocks (CheckedBlocks::Cached).
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "core/block_codec.hpp"
#include "core/checked_blocks.hpp"
#include "core/hash64.hpp"
#include "support/temp_dir.hpp"

using namespace penink;

namespace {

constexpr std::uint64_t block = 4096;

void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A file of two arrays: 10 blocks and a half at offset 4096, 3 blocks at offset 49152; bytes
// i * 7 + array.
struct TwoArrays {
    std::vector<std::uint8_t> file;
    std::vector<CheckedBlocks::Array> arrays{{4096, 10 * block + 2048}, {49152, 3 * block}};
    std::vector<std::uint64_t> sums;
    TwoArrays() {
        file.assign(49152 + 3 * block, 0);
        for (std::size_t k = 0; k < arrays.size(); ++k)
            for (std::uint64_t i = 0; i < arrays[k].bytes; ++i)
                file[arrays[k].offset + i] = std::uint8_t(i * 7 + k);
        for (const CheckedBlocks::Array& a : arrays)
            for (std::uint64_t at = 0; at < a.bytes; at += block)
                sums.push_back(hash64(file.data() + a.offset + at, std::size_t(std::min(block, a.bytes - at))));
    }
};

struct Fd {
    int fd;
    explicit Fd(const std::string& path) : fd(::open(path.c_str(), O_RDONLY)) {}
    ~Fd() { ::close(fd); }
};

// A test file's bytes written in a folder of their own and opened for reading.
struct OnDisk {
    test::TempDir dir;
    std::string path;
    Fd handle;
    explicit OnDisk(const std::vector<std::uint8_t>& bytes)
        : path(dir.file("f.bin")), handle((write_file(path, bytes), path)) {}
    int fd() const { return handle.fd; }
};

}  // namespace

TEST(CheckedBlocks, ReadsTheBlocksOfARangeOnce) {
    const TwoArrays f;
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays, block, f.sums);
    EXPECT_EQ(blocks.block_count(), 11u + 3u);
    EXPECT_EQ(blocks.bytes(), 10 * block + 2048 + 3 * block);
    EXPECT_EQ(blocks.bytes_read(), 0u);
    blocks.need(0, 5000, 9000);  // blocks 1 and 2
    EXPECT_EQ(blocks.bytes_read(), 2 * block);
    EXPECT_EQ(blocks.blocks_read(), 2u);
    EXPECT_FALSE(blocks.has_read(0, 4095));
    EXPECT_TRUE(blocks.has_read(0, 4096));
    EXPECT_TRUE(blocks.has_read(0, 3 * block - 1));
    EXPECT_FALSE(blocks.has_read(0, 3 * block));
    const auto* a = static_cast<const std::uint8_t*>(blocks.data(0));
    for (std::uint64_t i = 4096; i < 3 * block; ++i) ASSERT_EQ(a[i], std::uint8_t(i * 7)) << i;
    blocks.need(0, 6000, 7000);  // read already
    EXPECT_EQ(blocks.bytes_read(), 2 * block);
    blocks.need(0, 0, 10 * block + 2048);  // the rest of the array: 9 blocks, the last short
    EXPECT_EQ(blocks.bytes_read(), 10 * block + 2048);
    EXPECT_EQ(blocks.blocks_read(), 11u);
    for (std::uint64_t i = 0; i < 10 * block + 2048; ++i) ASSERT_EQ(a[i], std::uint8_t(i * 7)) << i;
    blocks.need(1, 3 * block - 1, 3 * block);
    const auto* b = static_cast<const std::uint8_t*>(blocks.data(1));
    EXPECT_EQ(b[3 * block - 1], std::uint8_t((3 * block - 1) * 7 + 1));
    EXPECT_EQ(blocks.bytes_read(), 11 * block + 2048);
}

TEST(CheckedBlocks, DamageIsFoundWhenItsBlockIsRead) {
    TwoArrays f;
    f.file[4096 + 5 * block + 17] ^= 1;  // block 5 of the first array
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays, block, f.sums);
    blocks.need(0, 0, 5 * block);  // blocks 0-4: sound
    blocks.need(1, 0, 3 * block);
    EXPECT_EQ(blocks.blocks_read(), 8u);
    try {
        blocks.need(0, 3 * block, 8 * block);  // 3, 4 read; 5 damaged; 6, 7 after it
        FAIL() << "no error";
    } catch (const DamagedBlockError& e) {
        EXPECT_EQ(e.file(), disk.path);
        EXPECT_EQ(std::string(e.what()), "penink: surface: " + disk.path +
                                             ": damaged cache: checksum mismatch in block 5 (bytes 24576 to 28672); "
                                             "remove it to have it rebuilt");
    }
    EXPECT_FALSE(blocks.has_read(0, 5 * block));
    EXPECT_THROW(blocks.need(0, 5 * block, 5 * block + 1), DamagedBlockError);  // again, on every read
    blocks.need(0, 6 * block, 11 * block);  // past it: sound
    EXPECT_EQ(blocks.blocks_read(), 13u);
}

TEST(CheckedBlocks, AFileCutShortIsDamageWhereItIsCut) {
    TwoArrays f;
    f.file.resize(49152 + block);  // the second array's last two blocks gone
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays, block, f.sums);
    blocks.need(0, 0, 10 * block + 2048);
    blocks.need(1, 0, block);
    EXPECT_THROW(blocks.need(1, block, 3 * block), DamagedBlockError);
}

namespace {

constexpr int once[1] = {1};  // floats differenced once (core/block_codec.hpp)

// A file of one coded array: 1000 floats (i * 0.5) in blocks of 64 (the last one of 40), coded
// (core/block_codec.hpp) back to back from offset 100.
struct CodedFile {
    std::vector<float> values;
    std::vector<std::uint8_t> file = std::vector<std::uint8_t>(100, 0xee);
    std::vector<std::uint32_t> sizes;
    std::vector<std::uint64_t> sums;
    CodedFile() {
        for (int i = 0; i < 1000; ++i) values.push_back(float(i) * 0.5f);
        for (std::size_t i = 0; i < values.size(); i += 64) {
            const std::vector<std::uint8_t> c = encode_floats(values.data() + i, std::min<std::size_t>(64, 1000 - i), once);
            sizes.push_back(std::uint32_t(c.size()));
            sums.push_back(hash64(c.data(), c.size()));
            file.insert(file.end(), c.begin(), c.end());
        }
    }
    std::vector<CheckedBlocks::CodedArray> arrays() const {
        CheckedBlocks::CodedArray a;
        a.offset = 100, a.sizes = sizes, a.elems = 1000, a.elem_bytes = 4, a.shift = 6;
        a.decode = [](const std::uint8_t* c, std::size_t size, void* out, std::uint64_t, std::size_t n) {
            return decode_floats(c, size, static_cast<float*>(out), n, once);
        };
        return {a};
    }
};

// CodedFile with block 2 replaced by a sound block of 32 floats, its size and checksum too: the
// checksum matches, the bytes do not decode to the block's 64 elements.
CodedFile undecodable_block_2() {
    CodedFile g;
    const std::size_t at = 100 + g.sizes[0] + g.sizes[1];
    const std::vector<std::uint8_t> shorter = encode_floats(g.values.data(), 32, once);
    g.file.erase(g.file.begin() + std::ptrdiff_t(at), g.file.begin() + std::ptrdiff_t(at + g.sizes[2]));
    g.file.insert(g.file.begin() + std::ptrdiff_t(at), shorter.begin(), shorter.end());
    g.sizes[2] = std::uint32_t(shorter.size()), g.sums[2] = hash64(shorter.data(), shorter.size());
    return g;
}

}  // namespace

// Elements of a coded array: a range reads (file bytes, counted) and decodes exactly its blocks.
TEST(CheckedBlocks, CodedArraysReadAndDecodeTheBlocksOfARange) {
    const CodedFile f;
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays(), f.sums);
    EXPECT_EQ(blocks.block_count(), 16u);
    EXPECT_EQ(blocks.bytes(), f.file.size() - 100);
    EXPECT_EQ(blocks.file_offset(0, 130), 100u + f.sizes[0] + f.sizes[1]);
    blocks.need(0, 100, 130);  // blocks 1 and 2
    EXPECT_EQ(blocks.bytes_read(), std::uint64_t(f.sizes[1] + f.sizes[2]));
    EXPECT_EQ(blocks.blocks_read(), 2u);
    EXPECT_FALSE(blocks.has_read(0, 63));
    EXPECT_TRUE(blocks.has_read(0, 64));
    EXPECT_TRUE(blocks.has_read(0, 191));
    EXPECT_FALSE(blocks.has_read(0, 192));
    const auto* v = static_cast<const float*>(blocks.data(0));
    for (int i = 64; i < 192; ++i) ASSERT_EQ(v[i], f.values[std::size_t(i)]) << i;
    blocks.need(0, 0, 1000);
    EXPECT_EQ(blocks.bytes_read(), blocks.bytes());
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(v[i], f.values[std::size_t(i)]) << i;
}

// Damage in a coded block is found by its checksum; coded bytes whose checksum matches but which
// do not decode to the block's elements (a foreign or mislabelled block) are damage as well.
TEST(CheckedBlocks, DamagedOrUndecodableCodedBlocksAreFound) {
    CodedFile f;
    f.file[100 + f.sizes[0] + f.sizes[1] + 2] ^= 4;  // block 2
    const OnDisk disk(f.file);
    {
        const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays(), f.sums);
        blocks.need(0, 0, 128);
        try {
            blocks.need(0, 100, 300);
            FAIL() << "no error";
        } catch (const DamagedBlockError& e) {
            EXPECT_NE(std::string(e.what()).find("checksum mismatch in block 2"), std::string::npos) << e.what();
        }
        blocks.need(0, 192, 1000);  // past it: sound
        EXPECT_FALSE(blocks.has_read(0, 128));
    }
    // block 2's coded bytes sound but not its 64 elements
    const CodedFile g = undecodable_block_2();
    const OnDisk other(g.file);
    const CheckedBlocks blocks(other.fd(), other.path, g.arrays(), g.sums);
    blocks.need(0, 192, 1000);  // the blocks after it are where the sizes say
    try {
        blocks.need(0, 128, 129);
        FAIL() << "no error";
    } catch (const DamagedBlockError& e) {
        EXPECT_NE(std::string(e.what()).find("undecodable data in block 2"), std::string::npos) << e.what();
    }
}

namespace {

// CodedFile's floats as pairs (value, index): the value decoded from the file, the index derived
// (CheckedBlocks::Deriver), as a node's x, y are derived from its grid.
std::vector<CheckedBlocks::CodedArray> derived_pairs(const CodedFile& f) {
    CheckedBlocks::CodedArray a = f.arrays()[0];
    a.elem_bytes = 8;
    a.decode = [](const std::uint8_t* c, std::size_t size, void* out, std::uint64_t, std::size_t n) {
        std::vector<float> v(n);
        if (!decode_floats(c, size, v.data(), n, once)) return false;
        for (std::size_t j = 0; j < n; ++j) static_cast<float*>(out)[2 * j] = v[j];
        return true;
    };
    a.derive = [](void* out, std::uint64_t first, std::uint64_t every, std::size_t n) {
        for (std::size_t j = 0; j < n; ++j) static_cast<float*>(out)[2 * j + 1] = float(first + j * every);
    };
    return {a};
}

// Elements begin, begin + every, ... (< end) of array k, read into place (need) and then taken
// from the mapping: what read_strided must give.
std::vector<std::uint8_t> needed_elements(const CheckedBlocks& blocks, int k, std::uint64_t elem_bytes,
                                          std::uint64_t begin, std::uint64_t end, std::uint64_t every) {
    blocks.need(k, begin, end);
    const auto* d = static_cast<const std::uint8_t*>(blocks.data(k));
    std::vector<std::uint8_t> out;
    for (std::uint64_t i = begin; i < end; i += every) out.insert(out.end(), d + i * elem_bytes, d + (i + 1) * elem_bytes);
    return out;
}

std::vector<std::uint8_t> strided(const CheckedBlocks& blocks, int k, std::uint64_t elem_bytes, std::uint64_t begin,
                                  std::uint64_t end, std::uint64_t every) {
    std::vector<std::uint8_t> out(std::size_t((end - begin + every - 1) / every * elem_bytes), 0xcd);
    blocks.read_strided(k, begin, end, every, out.data());
    return out;
}

}  // namespace

// A strided read gives exactly the elements need and the mapping give (decoded and derived, the
// last short block's too), reading each block holding one of them (counted) and leaving it
// unread in the mapping; a block already read is taken from the mapping (not read again); blocks
// holding none of them (a stride past a block) are not read.
TEST(CheckedBlocks, StridedReadsGiveTheNeededElementsWithoutKeepingTheirBlocks) {
    const CodedFile f;
    const OnDisk disk(f.file);
    const CheckedBlocks reference(disk.fd(), disk.path, derived_pairs(f), f.sums);
    const CheckedBlocks blocks(disk.fd(), disk.path, derived_pairs(f), f.sums);
    blocks.need(0, 64, 65);  // block 1 read into place
    const std::uint64_t before = blocks.bytes_read();
    ASSERT_EQ(before, f.sizes[1]);
    // every 7th from 10: elements in all 16 blocks, the last (960..999) short
    const std::vector<std::uint8_t> got = strided(blocks, 0, 8, 10, 1000, 7);
    ASSERT_EQ(got, needed_elements(reference, 0, 8, 10, 1000, 7));
    for (std::size_t j = 0; j < got.size() / 8; ++j) {
        float v[2];
        std::memcpy(v, got.data() + 8 * j, 8);
        ASSERT_EQ(v[0], f.values[10 + 7 * j]) << j;
        ASSERT_EQ(v[1], float(10 + 7 * j)) << j;
    }
    EXPECT_EQ(blocks.bytes_read(), blocks.bytes()) << "the 15 blocks not in place read, block 1 taken from the mapping";
    EXPECT_EQ(blocks.blocks_read(), 16u);
    for (std::uint64_t i = 0; i < 1000; i += 64) EXPECT_EQ(blocks.has_read(0, i), i == 64) << i;
    // every 150th: elements 0, 150, ..., 900 lie in blocks 0, 2, 4, 7, 9, 11, 14 alone
    const std::uint64_t read = blocks.bytes_read();
    ASSERT_EQ(strided(blocks, 0, 8, 0, 1000, 150), needed_elements(reference, 0, 8, 0, 1000, 150));
    std::uint64_t bytes = 0;
    for (const int b : {0, 2, 4, 7, 9, 11, 14}) bytes += f.sizes[std::size_t(b)];
    EXPECT_EQ(blocks.bytes_read() - read, bytes);
    // single elements, a range within one block, one at the array's end
    ASSERT_EQ(strided(blocks, 0, 8, 999, 1000, 3), needed_elements(reference, 0, 8, 999, 1000, 3));
    ASSERT_EQ(strided(blocks, 0, 8, 70, 120, 1), needed_elements(reference, 0, 8, 70, 120, 1));
    EXPECT_TRUE(strided(blocks, 0, 8, 5, 5, 2).empty());
    for (std::uint64_t i = 0; i < 1000; i += 64) EXPECT_EQ(blocks.has_read(0, i), i == 64) << i;
}

// On an array stored as it is (bytes): the file's bytes, none kept.
TEST(CheckedBlocks, StridedReadsOfAnUncodedArray) {
    const TwoArrays f;
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays, block, f.sums);
    blocks.need(0, 3 * block, 3 * block + 1);
    const std::vector<std::uint8_t> got = strided(blocks, 0, 1, 100, 10 * block + 2048, 1000);
    ASSERT_EQ(got.size(), (10 * block + 2048 - 100 + 999) / 1000);
    for (std::size_t j = 0; j < got.size(); ++j) ASSERT_EQ(got[j], std::uint8_t((100 + 1000 * j) * 7)) << j;
    for (std::uint64_t b = 0; b < 11; ++b) EXPECT_EQ(blocks.has_read(0, b * block), b == 3) << b;
    EXPECT_EQ(blocks.bytes_read(), 10 * block + 2048);
}

// A damaged or undecodable block met by a strided read throws DamagedBlockError naming it, as
// need does, at every read; the blocks before it stay unread in the mapping.
TEST(CheckedBlocks, StridedReadsFindDamage) {
    CodedFile f;
    f.file[100 + f.sizes[0] + f.sizes[1] + 2] ^= 4;  // block 2
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays(), f.sums);
    std::vector<float> out(200);
    for (int attempt = 0; attempt < 2; ++attempt) {
        try {
            blocks.read_strided(0, 0, 1000, 5, out.data());
            FAIL() << "no error";
        } catch (const DamagedBlockError& e) {
            EXPECT_EQ(e.file(), disk.path);
            EXPECT_NE(std::string(e.what()).find("checksum mismatch in block 2"), std::string::npos) << e.what();
        }
    }
    for (std::uint64_t i = 0; i < 1000; i += 64) EXPECT_FALSE(blocks.has_read(0, i)) << i;
    blocks.read_strided(0, 192, 1000, 5, out.data());  // past it: sound
    for (std::size_t j = 0; j < (1000 - 192 + 4) / 5; ++j) ASSERT_EQ(out[j], f.values[192 + 5 * j]) << j;
    // coded bytes whose checksum matches but which do not decode
    const CodedFile g = undecodable_block_2();
    const OnDisk other(g.file);
    const CheckedBlocks undecodable(other.fd(), other.path, g.arrays(), g.sums);
    try {
        undecodable.read_strided(0, 100, 300, 3, out.data());
        FAIL() << "no error";
    } catch (const DamagedBlockError& e) {
        EXPECT_NE(std::string(e.what()).find("undecodable data in block 2"), std::string::npos) << e.what();
    }
}

// Elements read one at a time through a cache of blocks give what need and the mapping give
// (decoded and derived, the last short block's too), leaving every block unread in the mapping;
// a block is read again only when another took its slot (one slot: every change of block reads;
// 16 slots: each of the 16 blocks once); a block already in the mapping is read there, not again.
TEST(CheckedBlocks, CachedElementReadsGiveTheNeededElementsWithoutKeepingTheirBlocks) {
    const CodedFile f;
    const OnDisk disk(f.file);
    const CheckedBlocks reference(disk.fd(), disk.path, derived_pairs(f), f.sums);
    const std::vector<std::uint8_t> all = needed_elements(reference, 0, 8, 0, 1000, 1);
    const auto element_is = [&](CheckedBlocks::Cached& c, std::uint64_t i) {
        return std::memcmp(c.element(i), all.data() + 8 * i, 8) == 0;
    };
    {
        const CheckedBlocks blocks(disk.fd(), disk.path, derived_pairs(f), f.sums);
        CheckedBlocks::Cached one(blocks, 0, 1);
        for (const std::uint64_t i : {5u, 6u, 63u}) ASSERT_TRUE(element_is(one, i)) << i;
        EXPECT_EQ(blocks.blocks_read(), 1u);
        ASSERT_TRUE(element_is(one, 999));  // the short last block
        ASSERT_TRUE(element_is(one, 7));    // block 0 again: its slot was taken
        EXPECT_EQ(blocks.blocks_read(), 3u);
        EXPECT_EQ(blocks.bytes_read(), std::uint64_t(2 * f.sizes[0] + f.sizes[15]));
        for (std::uint64_t i = 0; i < 1000; i += 64) EXPECT_FALSE(blocks.has_read(0, i)) << i;
    }
    {  // blocks a power of two apart (as rows of a padded square are) kept side by side: in
       // 4 slots indexed by block, blocks 0 and 4 would share one and be read at every turn
        const CheckedBlocks blocks(disk.fd(), disk.path, derived_pairs(f), f.sums);
        CheckedBlocks::Cached four(blocks, 0, 4);
        for (int turn = 0; turn < 3; ++turn)
            for (const std::uint64_t i : {10u, 4 * 64 + 10u}) ASSERT_TRUE(element_is(four, i)) << i;
        EXPECT_EQ(blocks.blocks_read(), 2u);
    }
    const CheckedBlocks blocks(disk.fd(), disk.path, derived_pairs(f), f.sums);
    blocks.need(0, 64, 65);  // block 1 in place
    CheckedBlocks::Cached many(blocks, 0, 16);
    for (int pass = 0; pass < 2; ++pass)
        for (std::uint64_t i = 0; i < 1000; i += 3) ASSERT_TRUE(element_is(many, i)) << i;
    EXPECT_EQ(blocks.blocks_read(), 16u) << "block 1 read by need, the other 15 once each";
    EXPECT_EQ(blocks.bytes_read(), blocks.bytes());
    EXPECT_EQ(many.element(70), static_cast<const std::uint8_t*>(blocks.data(0)) + 70 * 8) << "read in place";
    for (std::uint64_t i = 0; i < 1000; i += 64) EXPECT_EQ(blocks.has_read(0, i), i == 64) << i;
}

// A damaged block met by a cached read throws DamagedBlockError naming it, at every read (it is
// never kept), and an uncoded array's bytes are read as the file holds them.
TEST(CheckedBlocks, CachedElementReadsFindDamageAndReadUncodedArrays) {
    CodedFile f;
    f.file[100 + f.sizes[0] + f.sizes[1] + 2] ^= 4;  // block 2
    const OnDisk disk(f.file);
    const CheckedBlocks blocks(disk.fd(), disk.path, f.arrays(), f.sums);
    CheckedBlocks::Cached c(blocks, 0, 4);
    float v;
    std::memcpy(&v, c.element(65), 4);
    EXPECT_EQ(v, f.values[65]);
    for (int attempt = 0; attempt < 2; ++attempt) {
        try {
            c.element(130);
            FAIL() << "no error";
        } catch (const DamagedBlockError& e) {
            EXPECT_EQ(e.file(), disk.path);
            EXPECT_NE(std::string(e.what()).find("checksum mismatch in block 2"), std::string::npos) << e.what();
        }
    }
    std::memcpy(&v, c.element(200), 4);  // past it: sound
    EXPECT_EQ(v, f.values[200]);

    const TwoArrays t;
    const OnDisk other(t.file);
    const CheckedBlocks bytes(other.fd(), other.path, t.arrays, block, t.sums);
    CheckedBlocks::Cached b(bytes, 1, 2);
    for (const std::uint64_t i : {0u, 4095u, 4096u, 3 * 4096u - 1u, 17u})
        EXPECT_EQ(*b.element(i), std::uint8_t(i * 7 + 1)) << i;
    EXPECT_EQ(bytes.blocks_read(), 4u) << "blocks 0, 1, 2, then 0 again (its slot taken by block 2)";
    EXPECT_FALSE(bytes.has_read(1, 0));
}

// A coded array declaring the coded bytes of a whole block of one byte (CodedArray::fill_*):
// whole blocks of that size and checksum are taken as that byte without being read, by need, a
// strided read and a cached read alike (nothing read, nothing counted); the others, the short last
// block of that byte included, are read and checked. Their content is the same either way.
TEST(CheckedBlocks, BlocksKnownByTheirChecksumAreNotRead) {
    constexpr std::uint64_t per = 64, elems = 4 * per + 10;
    std::vector<std::uint8_t> values(elems, 1);
    for (std::uint64_t i = per; i < 2 * per; ++i) values[i] = std::uint8_t(i % 3);  // block 1 mixed
    std::vector<std::uint8_t> file(16, 0xee);
    CheckedBlocks::CodedArray a;
    a.offset = 16, a.elems = elems, a.elem_bytes = 1, a.shift = 6;
    a.decode = [](const std::uint8_t* c, std::size_t size, void* out, std::uint64_t, std::size_t n) {
        return decode_bytes(c, size, static_cast<std::uint8_t*>(out), n);
    };
    std::vector<std::uint64_t> sums;
    std::vector<std::uint32_t> sizes;
    for (std::uint64_t i = 0; i < elems; i += per) {
        const std::vector<std::uint8_t> c = encode_bytes(values.data() + i, std::size_t(std::min(per, elems - i)));
        sizes.push_back(std::uint32_t(c.size())), sums.push_back(hash64(c.data(), c.size()));
        file.insert(file.end(), c.begin(), c.end());
    }
    a.sizes = sizes;
    const std::vector<std::uint8_t> ones(per, 1), coded = encode_bytes(ones.data(), ones.size());
    a.fill_size = std::uint32_t(coded.size()), a.fill_sum = hash64(coded.data(), coded.size()), a.fill_byte = 1;
    ASSERT_EQ(sums[0], a.fill_sum);
    const OnDisk disk(file);
    {
        const CheckedBlocks blocks(disk.fd(), disk.path, {a}, sums);
        blocks.need(0, 0, elems);
        EXPECT_EQ(std::memcmp(blocks.data(0), values.data(), elems), 0);
        EXPECT_EQ(blocks.blocks_read(), 2u) << "block 1 and the short last block";
        EXPECT_EQ(blocks.bytes_read(), std::uint64_t(a.sizes[1] + a.sizes[4]));
    }
    {
        const CheckedBlocks blocks(disk.fd(), disk.path, {a}, sums);
        std::vector<std::uint8_t> every3((elems + 2) / 3);
        blocks.read_strided(0, 0, elems, 3, every3.data());
        for (std::size_t j = 0; j < every3.size(); ++j) ASSERT_EQ(every3[j], values[3 * j]) << j;
        EXPECT_EQ(blocks.blocks_read(), 2u);
        CheckedBlocks::Cached cached(blocks, 0, 8);
        for (std::uint64_t i = 0; i < elems; ++i) ASSERT_EQ(*cached.element(i), values[i]) << i;
        EXPECT_EQ(blocks.blocks_read(), 4u) << "blocks 1 and 4 again, into the cache";
    }
    // the same blocks without the declaration: every one read
    a.fill_sum = 0;
    const CheckedBlocks blocks(disk.fd(), disk.path, {a}, sums);
    blocks.need(0, 0, elems);
    EXPECT_EQ(std::memcmp(blocks.data(0), values.data(), elems), 0);
    EXPECT_EQ(blocks.blocks_read(), 5u);
}
