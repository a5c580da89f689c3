#include "core/checked_blocks.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
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
        s.derive = std::move(a.derive);
        if (!s.derive) s.fill_size = a.fill_size, s.fill_sum = a.fill_sum, s.fill_byte = a.fill_byte;
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

DamagedBlockError CheckedBlocks::damage(const Slot& a, std::uint64_t b, const char* what) const {
    return DamagedBlockError(path_, std::string("damaged cache: ") + what + " in block " + std::to_string(a.first + b) +
                                        " (bytes " + std::to_string(a.starts[b]) + " to " +
                                        std::to_string(a.starts[b + 1]) + "); remove it to have it rebuilt");
}

void CheckedBlocks::read_run(const Slot& a, std::uint64_t block, std::uint64_t end, std::uint8_t* in) const {
    const std::uint64_t from = a.starts[block], len = a.starts[end] - from;
    for (std::uint64_t got = 0; got < len;) {
        const ssize_t r = ::pread(fd_, in + got, std::size_t(len - got), off_t(from + got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
            std::uint64_t b = block;  // the block the file ends in (none of the run is checked yet)
            while (a.starts[b + 1] <= from + got) ++b;
            throw damage(a, b, "short read");
        }
        got += std::uint64_t(r);
    }
}

CheckedBlocks::BlockState CheckedBlocks::check_block(const Slot& a, std::uint64_t b, const std::uint8_t* c,
                                                     std::uint8_t* out) const {
    const std::size_t size = std::size_t(a.starts[b + 1] - a.starts[b]);
    if (hash64(c, size) != sums_[a.first + b]) return mismatch;
    const std::uint64_t per = std::uint64_t(1) << a.shift, n = std::min(per, a.elems - b * per);
    if (a.decode && !a.decode(c, size, out, b * per, std::size_t(n))) return undecodable;
    return sound;
}

void CheckedBlocks::load(int k, std::uint64_t block, std::uint64_t last) const {
    const Slot& a = arrays_[std::size_t(k)];
    const std::lock_guard<std::mutex> lock(mutex_);
    if (loaded_[a.first + block].load(std::memory_order_relaxed)) return;  // another thread read it meanwhile
    const std::uint64_t blocks = a.starts.size() - 1;
    if (block >= blocks) throw std::out_of_range("checked blocks: a block past the array's end");
    const std::uint64_t elems_per_block = std::uint64_t(1) << a.shift, block_bytes = elems_per_block * a.elem_bytes;
    std::uint8_t* dst = base_ + a.at + block * block_bytes;
    if (filled(a, block)) {  // known by its checksum: nothing read
        std::memset(dst, a.fill_byte, std::size_t(block_bytes));
        loaded_[a.first + block].store(true, std::memory_order_release);
        return;
    }
    // the run: unread blocks from `block` on, within [block, last] and max_run_bytes of the file
    std::uint64_t end = block + 1;
    const std::uint64_t stop = std::min(last + 1, blocks);
    while (end < stop && !loaded_[a.first + end].load(std::memory_order_relaxed) && !filled(a, end) &&
           a.starts[end + 1] - a.starts[block] <= max_run_bytes)
        ++end;
    const std::uint64_t from = a.starts[block], len = a.starts[end] - from;
    std::vector<std::uint8_t> coded;
    std::uint8_t* in = dst;  // an array stored as in memory is read into its place
    if (a.decode) coded.resize(std::size_t(len)), in = coded.data();
    read_run(a, block, end, in);
    // each block checked, then decoded: on all cores when the run is long (a window's rows)
    std::vector<BlockState> state(std::size_t(end - block), sound);
    parallel_chunks(state.size(), decode_chunk_blocks, [&](std::size_t j0, std::size_t j1) {
        for (std::size_t j = j0; j < j1; ++j) {
            const std::uint64_t b = block + j;
            std::uint8_t* out = dst + j * block_bytes;
            state[j] = check_block(a, b, in + (a.starts[b] - from), out);
            if (state[j] == sound && a.derive)
                a.derive(out, b * elems_per_block, 1, std::size_t(std::min(elems_per_block, a.elems - b * elems_per_block)));
        }
    });
    std::uint64_t good = 0;  // blocks of the run found sound, in order up to the first damaged one
    while (good < state.size() && state[good] == sound) ++good;
    for (std::uint64_t b = block; b < block + good; ++b) loaded_[a.first + b].store(true, std::memory_order_release);
    bytes_read_.fetch_add(a.starts[block + good] - from, std::memory_order_relaxed);
    if (good < state.size())
        throw damage(a, block + good, state[good] == mismatch ? "checksum mismatch" : "undecodable data");
    blocks_read_.fetch_add(end - block, std::memory_order_relaxed);
}

void CheckedBlocks::read_strided(int k, std::uint64_t begin, std::uint64_t end, std::uint64_t every, void* out,
                                 bool derive) const {
    if (begin >= end) return;
    every = std::max<std::uint64_t>(every, 1);
    const Slot& a = arrays_[std::size_t(k)];
    const std::uint64_t blocks = a.starts.size() - 1, last = (end - 1) >> a.shift;
    if (last >= blocks) throw std::out_of_range("checked blocks: a block past the array's end");
    const std::uint64_t per = std::uint64_t(1) << a.shift, eb = a.elem_bytes;
    // the first wanted element at or after element e
    const auto wanted_from = [&](std::uint64_t e) { return e <= begin ? begin : begin + (e - begin + every - 1) / every * every; };
    // whether block b holds a wanted element
    const auto holds = [&](std::uint64_t b) { return wanted_from(b * per) < std::min(end, (b + 1) * per); };
    auto* o = static_cast<std::uint8_t*>(out);
    thread_local std::vector<std::uint8_t> coded, decoded;
    for (std::uint64_t i = begin; i < end;) {
        const std::uint64_t block = i >> a.shift;
        if (loaded_[a.first + block].load(std::memory_order_acquire)) {  // copied from the mapping
            for (const std::uint64_t stop = std::min(end, (block + 1) * per); i < stop; i += every, o += eb)
                std::memcpy(o, base_ + a.at + i * eb, std::size_t(eb));
            continue;
        }
        if (filled(a, block)) {  // known by its checksum: nothing read
            for (const std::uint64_t stop = std::min(end, (block + 1) * per); i < stop; i += every, o += eb)
                std::memset(o, a.fill_byte, std::size_t(eb));
            continue;
        }
        // the run: unread blocks holding wanted elements from `block` on, within max_run_bytes of the file
        std::uint64_t run_end = block + 1;
        while (run_end <= last && !loaded_[a.first + run_end].load(std::memory_order_acquire) && holds(run_end) &&
               !filled(a, run_end) && a.starts[run_end + 1] - a.starts[block] <= max_run_bytes)
            ++run_end;
        const std::uint64_t from = a.starts[block];
        coded.resize(std::size_t(a.starts[run_end] - from));
        read_run(a, block, run_end, coded.data());
        bytes_read_.fetch_add(coded.size(), std::memory_order_relaxed);
        blocks_read_.fetch_add(run_end - block, std::memory_order_relaxed);
        decoded.resize(std::size_t(per * eb));
        for (std::uint64_t b = block; b < run_end; ++b) {
            const std::uint8_t* c = coded.data() + (a.starts[b] - from);
            if (const BlockState st = check_block(a, b, c, decoded.data()); st != sound)
                throw damage(a, b, st == mismatch ? "checksum mismatch" : "undecodable data");
            const std::uint8_t* elems = a.decode ? decoded.data() : c;  // an Array's bytes are its elements
            std::uint8_t* const first_out = o;
            const std::uint64_t first = i;
            for (const std::uint64_t stop = std::min(end, (b + 1) * per); i < stop; i += every, o += eb)
                std::memcpy(o, elems + (i - b * per) * eb, std::size_t(eb));
            if (derive && a.derive && o > first_out) a.derive(first_out, first, every, std::size_t((o - first_out) / eb));
        }
    }
}

CheckedBlocks::Cached::Cached(const CheckedBlocks& blocks, int k, std::size_t slots) : blocks_(&blocks), k_(k) {
    const Slot& a = blocks.arrays_[std::size_t(k)];
    slots = std::max<std::size_t>(slots, 1);
    tag_.assign(slots, 0);
    data_.resize(slots * (std::size_t(1) << a.shift) * std::size_t(a.elem_bytes));
    if (a.derive) words_ = ((std::size_t(1) << a.shift) + 63) / 64, derived_.assign(slots * words_, 0);
}

const std::uint8_t* CheckedBlocks::Cached::element(std::uint64_t i) {
    const CheckedBlocks& cb = *blocks_;
    const Slot& a = cb.arrays_[std::size_t(k_)];
    const std::uint64_t block = i >> a.shift, per = std::uint64_t(1) << a.shift, eb = a.elem_bytes;
    if (block + 1 >= a.starts.size()) throw std::out_of_range("checked blocks: a block past the array's end");
    if (cb.loaded_[a.first + block].load(std::memory_order_acquire)) return cb.base_ + a.at + i * eb;
    if (cb.filled(a, block)) {  // known by its checksum: nothing read
        fill_.assign(std::size_t(eb), a.fill_byte);
        return fill_.data();
    }
    // hashed (Fibonacci hashing): blocks a power of two apart, as the rows of the pyramid's padded
    // square that a coarse level's nodes lie on, would share one slot if mapped by index
    const std::uint64_t hash = ((block + 1) * 0x9E3779B97F4A7C15ull) >> 32;  // its top 32 bits, then scaled
    const std::size_t slot = std::size_t((hash * tag_.size()) >> 32);
    std::uint8_t* out = data_.data() + slot * std::size_t(per * eb);
    if (tag_[slot] != block + 1) {
        tag_[slot] = 0;
        coded_.resize(std::size_t(a.starts[block + 1] - a.starts[block]));
        cb.read_run(a, block, block + 1, coded_.data());
        cb.bytes_read_.fetch_add(coded_.size(), std::memory_order_relaxed);
        cb.blocks_read_.fetch_add(1, std::memory_order_relaxed);
        if (const BlockState st = cb.check_block(a, block, coded_.data(), out); st != sound)
            throw cb.damage(a, block, st == mismatch ? "checksum mismatch" : "undecodable data");
        if (!a.decode)  // an Array's bytes are its elements
            std::memcpy(out, coded_.data(), std::size_t(std::min(per, a.elems - block * per) * eb));
        std::fill_n(derived_.begin() + std::ptrdiff_t(slot * words_), words_, 0);
        tag_[slot] = block + 1;
    }
    const std::uint64_t j = i - block * per;
    if (a.derive) {
        std::uint64_t& bits = derived_[slot * words_ + std::size_t(j / 64)];
        if (!(bits >> (j % 64) & 1)) a.derive(out + j * eb, i, 1, 1), bits |= std::uint64_t(1) << (j % 64);
    }
    return out + j * eb;
}

}  // namespace penink
