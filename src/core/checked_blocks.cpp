#include "core/checked_blocks.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <new>
#include <stdexcept>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include "core/hash64.hpp"
#include "core/parallel_chunks.hpp"

namespace penink {

namespace {
constexpr std::uint64_t page_bytes = 4096;
constexpr std::uint64_t max_run_bytes = std::uint64_t(1) << 20;  // one pread at most
// Blocks of a run checked and decoded by one thread at least: a run of a few blocks (a frame's
// scattered nodes) stays on the calling thread, a long one (a window's rows) is shared out.
constexpr std::size_t decode_chunk_blocks = 64;
std::uint64_t round_up(std::uint64_t n, std::uint64_t a) { return (n + a - 1) / a * a; }
}  // namespace

CheckedBlocks::CheckedBlocks(int fd, std::string path, std::vector<Array> arrays, std::uint64_t block_bytes,
                             std::vector<std::uint64_t> sums)
    : path_(std::move(path)), sums_(std::move(sums)) {
    if (!std::has_single_bit(block_bytes) || block_bytes % page_bytes)
        throw std::invalid_argument("checked blocks: block size must be a power of two, a multiple of the page");
    for (const Array& a : arrays) {
        Slot s;
        s.elems = a.bytes, s.shift = unsigned(std::countr_zero(block_bytes));
        for (std::uint64_t at = 0; at < a.bytes; at += block_bytes) s.starts.push_back(a.offset + at);
        s.starts.push_back(a.offset + a.bytes);
        arrays_.push_back(std::move(s));
    }
    reserve(fd);
}

CheckedBlocks::CheckedBlocks(int fd, std::string path, std::vector<CodedArray> arrays, std::vector<std::uint64_t> sums)
    : path_(std::move(path)), sums_(std::move(sums)) {
    for (CodedArray& a : arrays) {
        if (a.shift > 30 || a.elem_bytes == 0 || !a.decode ||
            a.sizes.size() != ((a.elems + (std::uint64_t(1) << a.shift) - 1) >> a.shift))
            throw std::invalid_argument("checked blocks: one coded size per block of elements");
        Slot s;
        s.elems = a.elems, s.elem_bytes = a.elem_bytes, s.shift = a.shift, s.decode = std::move(a.decode);
        s.starts.reserve(a.sizes.size() + 1);
        s.starts.push_back(a.offset);
        for (const std::uint32_t n : a.sizes) s.starts.push_back(s.starts.back() + n);
        arrays_.push_back(std::move(s));
    }
    reserve(fd);
}

// The mapping every array decodes into, the loaded flags and the duplicated descriptor.
void CheckedBlocks::reserve(int fd) {
    std::size_t first = 0;
    std::uint64_t at = 0;
    for (Slot& s : arrays_) {
        s.first = first, s.at = at;
        first += s.starts.size() - 1;
        const std::uint64_t block = (std::uint64_t(1) << s.shift) * s.elem_bytes;
        at += round_up(std::max<std::uint64_t>(s.elems * s.elem_bytes, 1), std::max(block, page_bytes));
    }
    if (first != sums_.size()) throw std::invalid_argument("checked blocks: one checksum per block");
    mapped_ = std::size_t(std::max<std::uint64_t>(at, page_bytes));
    void* p = ::mmap(nullptr, mapped_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    base_ = static_cast<std::uint8_t*>(p);
    loaded_ = std::make_unique<std::atomic<bool>[]>(sums_.size());
    fd_ = ::fcntl(fd, F_DUPFD_CLOEXEC, 0);
    if (fd_ < 0) {
        ::munmap(base_, mapped_);
        throw std::runtime_error("checked blocks: cannot duplicate the file descriptor");
    }
}

CheckedBlocks::~CheckedBlocks() {
    if (base_) ::munmap(base_, mapped_);
    if (fd_ >= 0) ::close(fd_);
}

void CheckedBlocks::load(int k, std::uint64_t block, std::uint64_t last) const {
    const Slot& a = arrays_[std::size_t(k)];
    const std::lock_guard<std::mutex> lock(mutex_);
    if (loaded_[a.first + block].load(std::memory_order_relaxed)) return;  // another thread read it meanwhile
    const std::uint64_t blocks = a.starts.size() - 1;
    if (block >= blocks) throw std::out_of_range("checked blocks: a block past the array's end");
    // the run: unread blocks from `block` on, within [block, last] and max_run_bytes of the file
    std::uint64_t end = block + 1;
    const std::uint64_t stop = std::min(last + 1, blocks);
    while (end < stop && !loaded_[a.first + end].load(std::memory_order_relaxed) &&
           a.starts[end + 1] - a.starts[block] <= max_run_bytes)
        ++end;
    const std::uint64_t from = a.starts[block], len = a.starts[end] - from;
    const std::uint64_t elems_per_block = std::uint64_t(1) << a.shift, block_bytes = elems_per_block * a.elem_bytes;
    std::uint8_t* dst = base_ + a.at + block * block_bytes;
    std::vector<std::uint8_t> coded;
    std::uint8_t* in = dst;  // an array stored as in memory is read into its place
    if (a.decode) coded.resize(std::size_t(len)), in = coded.data();
    std::uint64_t good = 0;  // blocks of the run found sound
    const auto damaged = [&](const char* what, std::uint64_t b) {
        for (std::uint64_t g = block; g < block + good; ++g) loaded_[a.first + g].store(true, std::memory_order_release);
        bytes_read_.fetch_add(a.starts[block + good] - from, std::memory_order_relaxed);
        throw DamagedBlockError(path_, std::string("damaged cache: ") + what + " in block " +
                                           std::to_string(a.first + b) + " (bytes " + std::to_string(a.starts[b]) +
                                           " to " + std::to_string(a.starts[b + 1]) +
                                           "); remove it to have it rebuilt");
    };
    for (std::uint64_t got = 0; got < len;) {
        const ssize_t r = ::pread(fd_, in + got, std::size_t(len - got), off_t(from + got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
            std::uint64_t b = block;  // the block the file ends in (none of the run is checked yet)
            while (a.starts[b + 1] <= from + got) ++b;
            damaged("short read", b);
        }
        got += std::uint64_t(r);
    }
    // each block checked, then decoded: on all cores when the run is long (a window's rows)
    enum : std::uint8_t { sound, mismatch, undecodable };
    std::vector<std::uint8_t> state(std::size_t(end - block), sound);
    parallel_chunks(state.size(), decode_chunk_blocks, [&](std::size_t j0, std::size_t j1) {
        for (std::size_t j = j0; j < j1; ++j) {
            const std::uint64_t b = block + j;
            const std::uint8_t* c = in + (a.starts[b] - from);
            const std::size_t size = std::size_t(a.starts[b + 1] - a.starts[b]);
            if (hash64(c, size) != sums_[a.first + b]) {
                state[j] = mismatch;
                continue;
            }
            const std::uint64_t n = std::min(elems_per_block, a.elems - b * elems_per_block);
            if (a.decode && !a.decode(c, size, dst + j * block_bytes, b * elems_per_block, std::size_t(n)))
                state[j] = undecodable;
        }
    });
    for (; good < state.size(); ++good)  // the first damaged block, in order
        if (state[good] != sound) damaged(state[good] == mismatch ? "checksum mismatch" : "undecodable data", block + good);
    bytes_read_.fetch_add(len, std::memory_order_relaxed);
    blocks_read_.fetch_add(end - block, std::memory_order_relaxed);
    for (std::uint64_t b = block; b < end; ++b) loaded_[a.first + b].store(true, std::memory_order_release);
}

}  // namespace penink
