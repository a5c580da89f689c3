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

namespace penink {

namespace {
constexpr std::uint64_t page_bytes = 4096;
constexpr std::uint64_t max_run_bytes = std::uint64_t(1) << 20;  // one pread at most
std::uint64_t round_up(std::uint64_t n, std::uint64_t a) { return (n + a - 1) / a * a; }
}  // namespace

CheckedBlocks::CheckedBlocks(int fd, std::string path, std::vector<Array> arrays, std::uint64_t block_bytes,
                             std::vector<std::uint64_t> sums)
    : path_(std::move(path)), sums_(std::move(sums)) {
    if (!std::has_single_bit(block_bytes) || block_bytes % page_bytes)
        throw std::invalid_argument("checked blocks: block size must be a power of two, a multiple of the page");
    shift_ = unsigned(std::countr_zero(block_bytes));
    std::size_t first = 0;
    std::uint64_t at = 0;
    for (const Array& a : arrays) {
        arrays_.push_back({a.offset, a.bytes, at, first});
        first += std::size_t((a.bytes + block_bytes - 1) >> shift_);
        at += round_up(std::max<std::uint64_t>(a.bytes, 1), block_bytes);
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
    const std::uint64_t size = std::uint64_t(1) << shift_;
    const std::uint64_t blocks = (a.bytes + size - 1) >> shift_;
    if (block >= blocks) throw std::out_of_range("checked blocks: a block past the array's end");
    // the run: unread blocks from `block` on, within [block, last] and max_run_bytes
    std::uint64_t end = block + 1;
    const std::uint64_t stop = std::min({last + 1, blocks, block + std::max<std::uint64_t>(max_run_bytes >> shift_, 1)});
    while (end < stop && !loaded_[a.first + end].load(std::memory_order_relaxed)) ++end;
    const std::uint64_t begin = block << shift_, len = std::min(end << shift_, a.bytes) - begin;
    std::uint8_t* dst = base_ + a.at + begin;
    std::uint64_t good = 0;  // bytes of the run checked sound
    const auto damaged = [&](const char* what, std::uint64_t at) {
        for (std::uint64_t b = block; b < block + (good >> shift_); ++b) loaded_[a.first + b].store(true, std::memory_order_release);
        bytes_read_.fetch_add(good, std::memory_order_relaxed);
        const std::uint64_t from = a.offset + begin + at;
        throw DamagedBlockError(path_, std::string("damaged cache: ") + what + " in block " +
                                           std::to_string(a.first + block + (at >> shift_)) + " (bytes " +
                                           std::to_string(from) + " to " +
                                           std::to_string(std::min(from + size, a.offset + a.bytes)) +
                                           "); remove it to have it rebuilt");
    };
    for (std::uint64_t got = 0; got < len;) {
        const ssize_t r = ::pread(fd_, dst + got, std::size_t(len - got), off_t(a.offset + begin + got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) damaged("short read", got & ~(size - 1));
        got += std::uint64_t(r);
    }
    for (std::uint64_t b = block; b < end; ++b, good += size) {
        const std::uint64_t at = (b - block) << shift_;
        if (hash64(dst + at, std::size_t(std::min(size, len - at))) != sums_[a.first + b]) damaged("checksum mismatch", at);
    }
    bytes_read_.fetch_add(len, std::memory_order_relaxed);
    blocks_read_.fetch_add(end - block, std::memory_order_relaxed);
    for (std::uint64_t b = block; b < end; ++b) loaded_[a.first + b].store(true, std::memory_order_release);
}

}  // namespace penink
