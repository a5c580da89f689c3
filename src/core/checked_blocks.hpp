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
// blocks asked for together are read in one call.
// Thread-safe: blocks are loaded under a mutex, the loaded flags are atomic.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
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
    struct Array {
        std::uint64_t offset = 0;  // in the file, a multiple of the page size
        std::uint64_t bytes = 0;
    };
    // `fd` is duplicated (the caller keeps its own). `sums`: the blocks' checksums, array after
    // array. `block_bytes`: a power of two, a multiple of the page size. Throws std::bad_alloc
    // when the address space cannot be reserved.
    CheckedBlocks(int fd, std::string path, std::vector<Array> arrays, std::uint64_t block_bytes,
                  std::vector<std::uint64_t> sums);
    ~CheckedBlocks();
    CheckedBlocks(const CheckedBlocks&) = delete;
    CheckedBlocks& operator=(const CheckedBlocks&) = delete;

    // Where array k lives in memory (its bytes readable only once needed).
    const void* data(int k) const { return base_ + arrays_[std::size_t(k)].at; }
    // Makes bytes [begin, end) of array k readable, reading and checking the blocks not yet read.
    // Throws DamagedBlockError on a short read or a checksum mismatch.
    void need(int k, std::uint64_t begin, std::uint64_t end) const {
        if (begin >= end) return;
        const Slot& a = arrays_[std::size_t(k)];
        for (std::uint64_t b = begin >> shift_, last = (end - 1) >> shift_; b <= last; ++b)
            if (!loaded_[a.first + b].load(std::memory_order_acquire)) load(k, b, last);
    }
    // Bytes read from the file so far (blocks checked), and blocks of all arrays.
    std::uint64_t bytes_read() const { return bytes_read_.load(std::memory_order_relaxed); }
    std::uint64_t blocks_read() const { return blocks_read_.load(std::memory_order_relaxed); }
    std::uint64_t block_count() const { return sums_.size(); }
    // Bytes of all the arrays.
    std::uint64_t bytes() const {
        std::uint64_t n = 0;
        for (const Slot& a : arrays_) n += a.bytes;
        return n;
    }
    // Whether the block holding byte `at` of array k has been read (and found sound).
    bool has_read(int k, std::uint64_t at) const {
        return loaded_[arrays_[std::size_t(k)].first + (at >> shift_)].load(std::memory_order_acquire);
    }
    // Where array k starts in the file.
    std::uint64_t file_offset(int k) const { return arrays_[std::size_t(k)].offset; }
    const std::string& path() const { return path_; }

private:
    struct Slot {
        std::uint64_t offset, bytes, at;  // in the file; length; in the mapping
        std::size_t first;                // index of its first block in sums_ / loaded_
    };
    // Reads the run of blocks not yet read from `block` on (at most to `last`, and max_run_bytes)
    // in one pread, then checks them one by one.
    void load(int k, std::uint64_t block, std::uint64_t last) const;

    int fd_ = -1;
    std::string path_;
    std::vector<Slot> arrays_;
    unsigned shift_ = 16;
    std::vector<std::uint64_t> sums_;
    std::uint8_t* base_ = nullptr;
    std::size_t mapped_ = 0;
    std::unique_ptr<std::atomic<bool>[]> loaded_;
    mutable std::mutex mutex_;
    mutable std::atomic<std::uint64_t> bytes_read_{0}, blocks_read_{0};
};

}  // namespace penink
