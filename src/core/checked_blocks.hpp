// Arrays of a cache file read on demand: each array is cut into blocks (from its start, the last
// one short), each block with a hash64 checksum (core/hash64.hpp) known before any is read; a
// block is read (pread, never mapped: a file cut short meanwhile cannot fault the process) and
// checked when first needed, then kept for the life of this object. Untouched blocks cost no
// memory: the arrays live in one anonymous mapping reserved up front (MAP_NORESERVE), whose
// pages the kernel provides as they are written. (Their protection is never changed per block:
// scattered reads of page-sized blocks would split the mapping past the kernel's limit on
// mappings, vm.max_map_count. A reader that forgets to ask for a block reads zeros there; the
// tests compare frames drawn from a cache with frames drawn from memory.)
// Memory and time therefore follow the blocks a caller asks for, not the file. Neighbouring
// blocks asked for together are read in one call. An array may be stored coded
// (core/block_codec.hpp: fewer bytes in the file): its blocks then hold a power of two of
// elements each, their checksums are of the coded bytes, and a block is decoded into its place
// in the mapping once found sound. Part of a coded element may be derived rather than stored (a
// node's x, y from its grid): decode writes the stored part, derive the rest.
// A caller wanting every s-th element of a range (a sampled grid) reads them without loading:
// read_strided checks and decodes each block it touches into a scratch buffer of its thread and
// copies out the wanted elements (deriving only theirs), leaving the block unread in the mapping
// (which then costs no memory); a block already read is copied from the mapping.
// Thread-safe: blocks are loaded under a mutex, the loaded flags are atomic.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace penink {

// A block found damaged (short read or checksum mismatch) after the file was opened: an Error of
// stage "surface" naming the file, the block and its bytes, and saying that removing the file has
// it rebuilt; the caller rebuilds the cache (render) or reports it in one line (batch, bench).
class DamagedBlockError : public Error {
public:
    DamagedBlockError(const std::string& file, const std::string& what) : Error("surface", file, what) {}
};

class CheckedBlocks {
public:
    // An array stored as it is in memory: `bytes` bytes from `offset`, one element a byte.
    struct Array {
        std::uint64_t offset = 0;
        std::uint64_t bytes = 0;
    };
    // An array stored coded (core/block_codec.hpp): block after block from `offset`, each of
    // sizes[b] bytes in the file, decoding to 2^shift elements of elem_bytes bytes (the last block
    // short: elems in all). decode(coded, size, out, first, n) writes the n elements of a block
    // (their stored part, where the array has a Deriver), from element `first` of the array on, to
    // out; false when the coded bytes do not decode.
    using Decoder = std::function<bool(const std::uint8_t* coded, std::size_t size, void* out, std::uint64_t first,
                                       std::size_t n)>;
    // derive(out, first, every, n): the derived part of the n elements first, first + every, ...
    // of the array, out[j] being element first + j * every (their decoded part already there).
    using Deriver = std::function<void(void* out, std::uint64_t first, std::uint64_t every, std::size_t n)>;
    struct CodedArray {
        std::uint64_t offset = 0;
        std::span<const std::uint32_t> sizes;  // read by the constructor alone (a header's bytes)
        std::uint64_t elems = 0;
        std::uint32_t elem_bytes = 1;
        unsigned shift = 0;
        Decoder decode;
        Deriver derive;  // empty: the decoder writes whole elements
        // A whole block of elements whose every byte is fill_byte codes to fill_size bytes of
        // checksum fill_sum (0: none given; an array without a Deriver): a block of that size and
        // checksum (both known before any block is read) is taken to hold that without being read,
        // checked or decoded. A terrain cache's valid flags: most blocks of most DEMs are all valid.
        std::uint32_t fill_size = 0;
        std::uint64_t fill_sum = 0;
        std::uint8_t fill_byte = 0;
    };
    // `fd` is duplicated (the caller keeps its own). `sums`: the blocks' checksums, array after
    // array. `block_bytes`: a power of two, a multiple of the page size. Throws std::bad_alloc
    // when the address space cannot be reserved.
    CheckedBlocks(int fd, std::string path, std::vector<Array> arrays, std::uint64_t block_bytes,
                  std::vector<std::uint64_t> sums);
    // Coded arrays: `sums` the checksums of the blocks' coded bytes, array after array.
    CheckedBlocks(int fd, std::string path, std::vector<CodedArray> arrays, std::vector<std::uint64_t> sums);
    ~CheckedBlocks();
    CheckedBlocks(const CheckedBlocks&) = delete;
    CheckedBlocks& operator=(const CheckedBlocks&) = delete;

    // Where array k lives in memory, decoded (its elements readable only once needed).
    const void* data(int k) const { return base_ + arrays_[std::size_t(k)].at; }
    // Makes elements [begin, end) of array k readable (bytes, for an Array), reading, checking and
    // decoding the blocks not yet read. Throws DamagedBlockError on a short read, a checksum
    // mismatch or a block that does not decode.
    void need(int k, std::uint64_t begin, std::uint64_t end) const {
        if (begin >= end) return;
        const Slot& a = arrays_[std::size_t(k)];
        for (std::uint64_t b = begin >> a.shift, last = (end - 1) >> a.shift; b <= last; ++b)
            if (!loaded_[a.first + b].load(std::memory_order_acquire)) load(k, b, last);
    }
    // Elements begin, begin + every, ... (< end) of array k into out, one after the other
    // ((end - begin + every - 1) / every elements; bytes, for an Array), leaving the blocks not
    // yet read unread: each is read, checked and decoded into a scratch buffer (its bytes counted
    // by bytes_read, again at every call), a block already read is copied from the mapping.
    // Without `derive`, the derived part of the elements of blocks not yet read is left as the
    // decoder left it (for a caller reading the stored part alone: a node's height).
    // Throws DamagedBlockError as need does.
    void read_strided(int k, std::uint64_t begin, std::uint64_t end, std::uint64_t every, void* out,
                      bool derive = true) const;
    // The derived part of elements first, first + every, ... (n of them) of array k into out
    // (out[j]: element first + j * every; their stored part left as it is), read from no block;
    // false (nothing written) for an array without a Deriver.
    bool derive(int k, std::uint64_t first, std::uint64_t every, std::size_t n, void* out) const {
        const Slot& a = arrays_[std::size_t(k)];
        if (!a.derive) return false;
        if (n > 0) a.derive(out, first, every, n);
        return true;
    }
    // Bytes read from the file so far (blocks checked), and blocks of all arrays.
    std::uint64_t bytes_read() const { return bytes_read_.load(std::memory_order_relaxed); }
    std::uint64_t blocks_read() const { return blocks_read_.load(std::memory_order_relaxed); }
    std::uint64_t block_count() const { return sums_.size(); }
    // Bytes of all the arrays in the file.
    std::uint64_t bytes() const {
        std::uint64_t n = 0;
        for (const Slot& a : arrays_) n += a.starts.back() - a.starts.front();
        return n;
    }
    // Whether the block holding element `at` of array k has been read (and found sound).
    bool has_read(int k, std::uint64_t at) const {
        const Slot& a = arrays_[std::size_t(k)];
        return loaded_[a.first + (at >> a.shift)].load(std::memory_order_acquire);
    }
    // Where array k starts in the file, and where the block holding its element `at` does.
    std::uint64_t file_offset(int k) const { return arrays_[std::size_t(k)].starts.front(); }
    std::uint64_t file_offset(int k, std::uint64_t at) const {
        const Slot& a = arrays_[std::size_t(k)];
        return a.starts[std::size_t(at >> a.shift)];
    }
    const std::string& path() const { return path_; }

    // Elements of array k read one at a time without loading their blocks into the mapping: a
    // block not yet read is read, checked and decoded (its elements derived) into a small cache of
    // `slots` blocks, each block in one slot given by a hash of its index (a later block in the same
    // slot replaces it; the hash spreads blocks a power of two apart, which indexing would put in
    // one slot: on a whole view of a 117 M-node DEM the pyramid's errors were decoded 150 k times
    // from 38 k blocks, 42 k hashed), so
    // scattered reads over a whole grid (the nodes of a coarse mesh, a few in each block) hold the
    // cache, not every block they touch; a block already in the mapping is read there. A cached
    // block's derived part (a node's x, y) is derived element by element as they are asked for. Its bytes
    // count in bytes_read each time it is read into the cache. Throws DamagedBlockError as need
    // does. One reader per thread (the CheckedBlocks it reads may be shared).
    class Cached {
    public:
        Cached(const CheckedBlocks& blocks, int k, std::size_t slots);
        // The bytes of element i (elem_bytes of them; a byte for an Array), valid until the next call.
        const std::uint8_t* element(std::uint64_t i);

    private:
        const CheckedBlocks* blocks_;
        int k_;
        std::vector<std::uint64_t> tag_;   // block held by each slot, plus 1; 0: empty
        std::vector<std::uint8_t> data_;   // slots x block bytes, decoded
        std::vector<std::uint64_t> derived_;  // slots x words: a bit per element derived (arrays with a Deriver)
        std::size_t words_ = 0;
        std::vector<std::uint8_t> coded_;  // scratch: a block's file bytes
        std::vector<std::uint8_t> fill_;   // an element of a block known by its checksum (CodedArray::fill_sum)
    };

private:
    struct Slot {
        std::vector<std::uint64_t> starts;  // file offset of each block, then the array's end
        std::uint64_t elems = 0, elem_bytes = 1, at = 0;  // elements, bytes of one; offset in the mapping
        unsigned shift = 0;                 // 2^shift elements a block
        std::size_t first = 0;              // index of its first block in sums_ / loaded_
        Decoder decode;  // empty: stored as in memory
        Deriver derive;  // empty: nothing derived
        std::uint32_t fill_size = 0;        // CodedArray's
        std::uint64_t fill_sum = 0;
        std::uint8_t fill_byte = 0;
    };
    // Whether block b of `a` is a whole block of fill_byte by its size and checksum (CodedArray).
    bool filled(const Slot& a, std::uint64_t b) const {
        return a.fill_sum != 0 && sums_[a.first + b] == a.fill_sum && a.starts[b + 1] - a.starts[b] == a.fill_size &&
               ((b + 1) << a.shift) <= a.elems;
    }
    enum BlockState : std::uint8_t { sound, mismatch, undecodable };
    void reserve(int fd);
    // Reads the run of blocks not yet read from `block` on (at most to `last`, and max_run_bytes)
    // in one pread, then checks (and decodes) them one by one.
    void load(int k, std::uint64_t block, std::uint64_t last) const;
    // Reads blocks [block, end) of `a` (their file bytes, back to back) into `in`; throws
    // DamagedBlockError on a short read.
    void read_run(const Slot& a, std::uint64_t block, std::uint64_t end, std::uint8_t* in) const;
    // Checks block b of `a` (its file bytes at c) and decodes it to out (an Array's bytes are
    // left where they are): sound, or why not. Nothing derived.
    BlockState check_block(const Slot& a, std::uint64_t b, const std::uint8_t* c, std::uint8_t* out) const;
    // The error for block b of `a` found damaged (`what`).
    DamagedBlockError damage(const Slot& a, std::uint64_t b, const char* what) const;

    int fd_ = -1;
    std::string path_;
    std::vector<Slot> arrays_;
    std::vector<std::uint64_t> sums_;
    std::uint8_t* base_ = nullptr;
    std::size_t mapped_ = 0;
    std::unique_ptr<std::atomic<bool>[]> loaded_;
    mutable std::mutex mutex_;
    mutable std::atomic<std::uint64_t> bytes_read_{0}, blocks_read_{0};
};

}  // namespace penink
